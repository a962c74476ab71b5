#!/usr/bin/env bash
# Rate-dependent sections: the explicit step of an N x N polyurea sheet
# (bench/membrane/gvbo.toml: 1 m, 1 mm, clamped, (1,1) mode + 50 kPa follower
# pressure, 2 N^2 triangles) with a GVBO section (polyurea-gvbo, the polyurea
# chapter's Table 5) against the same sheet linear elastic at the GVBO rest
# moduli (polyurea-elastic-rest), at 1 and 2 threads: best and median wall
# and mean CPU per step (ms), their ratio (target: GVBO at most 4x elastic)
# and the GVBO cost per element and step. Runs membrane_kernels N T STEPS law.
# The machine may be shared: run it on a quiet machine; the ratio comes from
# one process, the two sheets timed one after the other.
# Usage: bash bench/membrane/gvbo.sh [BUILD_DIR]   env: SIZES="300" STEPS=20
set -euo pipefail
BUILD="${1:-build}"
cd "$(dirname "$0")/../.."
KERNELS="$BUILD/bin/membrane_kernels"
SIZES="${SIZES:-300}"
STEPS="${STEPS:-20}"
if [ ! -x "$KERNELS" ]; then
  echo "gvbo.sh: $KERNELS not found: cmake --build $BUILD --target membrane_kernels" >&2
  exit 1
fi
echo "membrane GVBO bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), steps $STEPS"
for n in $SIZES; do
  for th in 1 2; do
    echo "--- N=$n threads=$th (load $(cut -d' ' -f1-3 /proc/loadavg))"
    OMP_NUM_THREADS=$th "$KERNELS" "$n" "$th" "$STEPS" law
  done
done
