#!/usr/bin/env bash
# Benchmark (not a test) of a yarn's law following its path (follow_path,
# micro/yarn_orientation.hpp): BENCH_BASELINE (an older homogenize binary,
# required) against BUILD/bin/homogenize in alternating runs on
#   cases/cells/plain-weave.toml     isotropic yarns: the fast path, no
#                                    per-voxel entries (expected: no change)
#   cases/cells/plain-weave-ti.toml  transversely isotropic yarns: the
#                                    baseline uses the law as given, the new
#                                    binary rotates it per voxel
# at the cells' resolution (64 x 64 x 16). One line per run: binary, cell,
# wall (s), solver wall_s, iterations per load case, peak RSS (kB); then the
# median ratios new / old per cell.
# Usage: BENCH_BASELINE=/path/to/old/homogenize bash bench/homogenize/yarn_path.sh [BUILD_DIR]
# Env: BENCH_PAIRS (5), BENCH_THREADS (2), BENCH_TOL (1e-5, the default)
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-yarn-path "${1:-build}"
OLD="${BENCH_BASELINE:?set BENCH_BASELINE to an older homogenize binary}"
PAIRS="${BENCH_PAIRS:-5}"
THREADS="${BENCH_THREADS:-2}"
TOL="${BENCH_TOL:-1e-5}"
LIB="$OUT/library.toml"
RES="$OUT/runs.txt"
: > "$RES"
echo "$(bench_machine), $PAIRS pairs, $THREADS threads, tol $TOL"

# one BIN CELL: one run, one line in $RES
one() {
  local bin="$1" cell="$2" tag="$3"
  local start end
  start=$(date +%s.%N)
  /usr/bin/time -f "%M" -o "$OUT/rss.txt" "$bin" "$cell" --name bench --library "$LIB" \
    --overwrite --threads "$THREADS" --tol "$TOL" --json --quiet > "$OUT/last.json"
  end=$(date +%s.%N)
  /usr/bin/python3 - "$OUT/last.json" "$tag" "$(basename "$cell")" "$start" "$end" \
    "$(cat "$OUT/rss.txt")" <<'PY' | tee -a "$RES"
import json, sys
text = open(sys.argv[1]).read()
d = json.loads(text[text.index('{'):text.rindex('}') + 1])
wall = float(sys.argv[5]) - float(sys.argv[4])
print(sys.argv[2], sys.argv[3], "%.2f" % wall, "%.2f" % d["wall_s"],
      ",".join(str(i) for i in d["iterations"]), sys.argv[6])
PY
}

for cell in cases/cells/plain-weave.toml cases/cells/plain-weave-ti.toml; do
  for p in $(seq "$PAIRS"); do
    if [ $((p % 2)) = 1 ]; then
      one "$OLD" "$cell" old
      one "$BIN" "$cell" new
    else
      one "$BIN" "$cell" new
      one "$OLD" "$cell" old
    fi
  done
done
echo "$(bench_machine) (end)"
/usr/bin/python3 - "$RES" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
for cell in sorted({r[1] for r in rows}):
    def col(tag, i):
        return [float(r[i]) for r in rows if r[1] == cell and r[0] == tag]
    ratios = {}
    for name, i in (("wall", 2), ("solver", 3), ("rss", 5)):
        old, new = col("old", i), col("new", i)
        # pairs in run order: median of the per-pair ratios
        ratios[name] = statistics.median(n / o for n, o in zip(new, old))
    print("%s: new/old median per-pair ratio wall %.3f, solver %.3f, peak RSS %.3f"
          % (cell, ratios["wall"], ratios["solver"], ratios["rss"]))
PY
