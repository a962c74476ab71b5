#!/usr/bin/env bash
# Benchmark of the nonlinear FFT homogenizer (not a test): the polyurea cell
# (cases/cells/polyurea.toml: GVBO soft domains, elastic hard ellipsoids) at
# 64^3 under 100 load steps of uniaxial strain at 1e4 /s to 0.1 with 2
# threads: wall time, Newton and CG iterations per step, peak memory.
# Usage: bash bench/homogenize/nonlinear.sh [BUILD_DIR]
# Env: BENCH_N (default 64), BENCH_THREADS (2), BENCH_STEPS (100),
#      BENCH_TOL (1e-5), BENCH_ETA (0.1), BENCH_OUT (BUILD/bench-nonlinear).
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-nonlinear "${1:-build}"
N="${BENCH_N:-64}"
T="${BENCH_THREADS:-2}"
STEPS="${BENCH_STEPS:-100}"
TOL="${BENCH_TOL:-1e-5}"
ETA="${BENCH_ETA:-0.1}"
echo "nonlinear homogenize bench: ${N}^3, $T threads, $STEPS steps, tol $TOL, eta $ETA," \
  "$(bench_machine)"
/usr/bin/time -v "$BIN" cases/cells/polyurea.toml --resolution "$N" --threads "$T" \
  --path uniaxial-strain --rate 1e4 --to 0.1 --steps "$STEPS" --tol "$TOL" --eta "$ETA" \
  --quiet --out "$OUT/history.csv" 2> "$OUT/time.txt" | tee "$OUT/summary.txt"
/usr/bin/python3 - "$OUT/history.csv" "$OUT/time.txt" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))[1:]
newton = [int(r["newton"]) for r in rows]
krylov = [int(r["krylov"]) for r in rows]
wall = [float(r["wall_s"]) for r in rows]
rss = [l for l in open(sys.argv[2]) if "Maximum resident" in l][0].split(":")[1].strip()
elapsed = [l for l in open(sys.argv[2]) if "Elapsed (wall" in l][0].split("):")[1].strip()
cpu = [l for l in open(sys.argv[2]) if "Percent of CPU" in l][0].split(":")[1].strip()
print("steps %d: wall %s (CPU %s), peak %.0f MiB" % (len(rows), elapsed, cpu, int(rss) / 1024))
print("Newton per step: mean %.2f, min %d, max %d; CG per step: mean %.1f, min %d, max %d"
      % (sum(newton) / len(rows), min(newton), max(newton), sum(krylov) / len(rows),
         min(krylov), max(krylov)))
print("CG per Newton step: %.1f; step wall: mean %.3f s, first %.3f s" %
      (sum(krylov) / max(sum(newton), 1), sum(wall) / len(rows), wall[0]))
print("first steps (newton, krylov):", list(zip(newton[:5], krylov[:5])))
print("final E_xx %s Sigma_xx %.4g MPa" % (rows[-1]["eps_xx"], float(rows[-1]["sig_xx"]) / 1e6))
PY
