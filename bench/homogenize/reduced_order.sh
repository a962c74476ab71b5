#!/usr/bin/env bash
# Benchmark of the reduced-order cell (not a test): the one-off build of the
# chapter's two-scale polyurea cell (cases/cells/polyurea-two-scale.toml,
# 32^3) at 1 and 8 partitions per phase (2 and 16 partitions: solves, CG
# iterations, seconds, peak memory), in both schemes (tfa, clustering), then
# one material-point step of each entry against one full-field step of the
# same history on the same voxels
# (homogenize_rom_bench: confined compression and shear at 2.6e3 /s to 0.3
# in 60 steps, the full field on BENCH_THREADS threads), with the law
# updates per step of both sides, at each reduced-order Newton tolerance of
# BENCH_ROM_TOLS (the law's default 1e-10, and the full field's own 1e-5).
# Usage: bash bench/homogenize/reduced_order.sh [BUILD_DIR]
# Env: BENCH_N (32), BENCH_THREADS (1), BENCH_ROM_TOLS ("1e-10 1e-5"),
# BENCH_OUT (BUILD/bench-reduced-order).
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-reduced-order "${1:-build}"
N="${BENCH_N:-32}"
T="${BENCH_THREADS:-1}"
TOLS="${BENCH_ROM_TOLS:-1e-10 1e-5}"
LIB="$OUT/library.toml"
rm -rf "$LIB" "$LIB.lock" "$OUT/library.side"
echo "reduced-order bench: ${N}^3, full field on $T thread(s), $(bench_machine)"
for scheme in tfa clustering; do
  for k in 1 8; do
    "$BIN" cases/cells/polyurea-two-scale.toml --resolution "$N" --library "$LIB" \
      --name "rom-$scheme-k$k" --reduced-order --partitions "$k" --scheme "$scheme" --quiet |
      grep -E "^(rom|solves|state)"
  done
done
for tol in $TOLS; do
  for path in confined shear; do
    "$BUILD/bin/homogenize_rom_bench" "$LIB" rom-tfa-k1,rom-tfa-k8,rom-clustering-k1,rom-clustering-k8 \
      cases/cells/polyurea-two-scale.toml \
      "$N" "$T" "$path" 2.6e3 0.3 60 3 "$tol"
  done
done
