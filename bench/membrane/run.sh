#!/usr/bin/env bash
# Membrane benchmark (Newmark and explicit steps): structured N x N squares (2 triangles
# each), isotropic E = 1 GPa, nu = 0.3, rho = 1000, h = 1 mm, fixed edges,
# centre strike at 1 m/s, tau = 0.4 h_el / c_S, STEPS steps (default 200).
# 1. `membrane run` end to end: assembly, set-up and per-step times, CG
#    iterations and peak memory for 1 and 2 threads, and at N <= 300 the
#    largest difference of the probe histories between the CG run and the
#    factorized (CHOLMOD) solve.
# 2. membrane_kernels (bench/membrane/kernels.cpp) at KERNEL_SIZES: one
#    product with K in each storage (the 3x3-block one is the memory floor
#    of a step) and the Newmark step, best and median wall and CPU per call.
# 3. bench/membrane/gvbo.sh at GVBO_SIZES: the explicit step of a GVBO
#    polyurea sheet against the same sheet elastic, 1 and 2 threads.
# The machine may be shared: compare against a baseline run in the same
# session (alternate the binaries), not against old figures.
# Usage: bash bench/membrane/run.sh [BUILD_DIR]
#   env: SIZES="100 300 800" STEPS=200 KERNEL_SIZES="300" GVBO_SIZES="300" GVBO_STEPS=20
set -euo pipefail
BUILD="${1:-build}"
cd "$(dirname "$0")/../.."
BIN="$BUILD/bin/membrane"
CASE=bench/membrane/bench.toml
SIZES="${SIZES:-100 300 800}"
STEPS="${STEPS:-200}"
KERNEL_SIZES="${KERNEL_SIZES:-300}"
OUT="$(mktemp -d /tmp/lamina-bench-membrane.XXXXXX)"
LIB="$OUT/empty-library.toml"   # inline material: never touch the user's library
trap 'rm -rf "$OUT"' EXIT

run() { # name threads N extra-args...
  local name=$1 th=$2 n=$3; shift 3
  local dt te
  dt=$(python3 -c "import math; c=math.sqrt(1e9/(2*1.3)/1000); print(repr(0.4/$n/c))")
  te=$(python3 -c "print(repr($STEPS*$dt))")
  OMP_NUM_THREADS=$th /usr/bin/time -f "%M" -o "$OUT/$name.mem" "$BIN" run "$CASE" \
    --out "$OUT/$name" --library "$LIB" --json --set mesh.nx="$n" --set time.dt="$dt" \
    --set time.t_end="$te" "$@" > "$OUT/$name.json"
  python3 - "$OUT/$name.json" "$OUT/$name.mem" "$n" "$th" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); mem = int(open(sys.argv[2]).read().split()[-1]) / 1024
print("%-14s N=%-4s threads=%s dofs=%-8d assembly=%.3f s  setup=%.3f s  step=%.2f ms  iters=%.1f  peak=%.0f MB"
      % (sys.argv[5], sys.argv[3], sys.argv[4], d["dofs"], d["assembly_s"], d["factor_s"],
         1e3 * d["step_s"], d["solver"]["mean_iterations"], mem))
PY
}

compare() { # reference other
  python3 - "$OUT/$1/probes.csv" "$OUT/$2/probes.csv" <<'PY'
import csv, sys
a = [[float(x) for x in r[1:]] for r in list(csv.reader(open(sys.argv[1])))[1:]]
b = [[float(x) for x in r[1:]] for r in list(csv.reader(open(sys.argv[2])))[1:]]
scale = max(abs(x) for r in a for x in r)
diff = max(abs(x - y) for ra, rb in zip(a, b) for x, y in zip(ra, rb))
print("  CG vs factorized: max |difference| / max |value| over all probe histories = %.2e" % (diff / scale))
PY
}

echo "membrane bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), steps $STEPS"
for n in $SIZES; do
  for th in 1 2; do run "cg-$n-$th" "$th" "$n"; done
  if [ "$n" -le 300 ]; then
    run "chol-$n" 1 "$n" --set solver.type='"cholesky"'
    compare "chol-$n" "cg-$n-1"
  fi
done
if [ -x "$BUILD/bin/membrane_kernels" ]; then
  for n in $KERNEL_SIZES; do
    for th in 1 2; do
      echo "--- kernels N=$n threads=$th (load $(cut -d' ' -f1-3 /proc/loadavg))"
      OMP_NUM_THREADS=$th "$BUILD/bin/membrane_kernels" "$n" "$th" 40
    done
  done
fi
SIZES="${GVBO_SIZES:-300}" STEPS="${GVBO_STEPS:-20}" bash bench/membrane/gvbo.sh "$BUILD"
