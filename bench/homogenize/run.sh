#!/usr/bin/env bash
# Benchmark of the FFT homogenizer (not a test): wall time, iterations per
# load case and peak memory for the sphere and polyurea cells at 64^3 and
# 128^3 with 1 and 2 threads, a contrast sweep of the sphere to inclusion
# E = 156 GPa, and the resolution study of the sphere cell (32^3 against the
# Richardson extrapolation from 64^3, 128^3 and, with BENCH_256=1, 256^3).
# Usage: bash bench/homogenize/run.sh [BUILD_DIR]      (make bench runs it)
# Then one CG iteration against the FFT floor (homogenize_kernels) and, with
# BENCH_BASELINE=<an older homogenize binary>, old against new on the 128^3
# sphere cell in alternating runs (the FANS comparison of the README).
# Env: BENCH_TOL (default 1e-5: C to 5 significant digits), BENCH_256=1,
#      BENCH_QUICK=1 (64^3 only), BENCH_OUT (default BUILD/bench-homogenize),
#      BENCH_BASELINE, BENCH_PAIRS (3), BENCH_PAIR_THREADS (2), BENCH_OLD_TOL (1e-3), BENCH_NEW_TOL
#      (1e-3: each the loosest decade tolerance with C within 5e-6 of max|C|
#      of its own tol 1e-8 answer, as FANS's 1e-2 in the FANS comparison).
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-homogenize "${1:-build}"
TOL="${BENCH_TOL:-1e-5}"
LIB="$OUT/library.toml"
rm -f "$LIB" "$LIB.lock"
RES="$OUT/results.jsonl"
export LAMINA_FFTW_WISDOM="$OUT/fftw-wisdom"   # fresh plans: planning is measured below
rm -f "$LAMINA_FFTW_WISDOM"
: > "$RES"
SIZES="64 128"
[ "${BENCH_QUICK:-0}" = 1 ] && SIZES="64"

# run NAME CELL N THREADS [extra args]: one homogenization, one JSON line in $RES
run() {
  local name="$1" cell="$2" n="$3" threads="$4"
  shift 4
  local tfile="$OUT/time-$name-$n-$threads.txt"
  /usr/bin/time -v "$BIN" "$cell" --name "$name-$n-t$threads" --library "$LIB" --overwrite \
    --resolution "$n" --threads "$threads" --tol "$TOL" --json --quiet "$@" \
    2>"$tfile" > "$OUT/last.json"
  local rss
  rss=$(awk -F: '/Maximum resident/ {gsub(/ /, "", $2); print $2}' "$tfile")
  /usr/bin/python3 - "$OUT/last.json" "$name" "$n" "$threads" "$rss" >> "$RES" <<'PY'
import json, sys
j = json.loads(open(sys.argv[1]).read().splitlines()[-1])
j.update(case=sys.argv[2], n=int(sys.argv[3]), threads=int(sys.argv[4]), rss_kb=int(sys.argv[5]))
print(json.dumps(j))
PY
  tail -n 1 "$RES" | /usr/bin/python3 -c '
import json, sys
j = json.loads(sys.stdin.read())
print("%-16s %4d^3 %d thr  wall %7.2f s  peak %7.0f MiB  iterations %s  C11 %.6g  C44 %.6g" % (
    j["case"], j["n"], j["threads"], j["wall_s"], j["rss_kb"] / 1024, j["iterations"],
    j["C"][0][0], j["C"][3][3]))'
}

echo "homogenize bench: tol $TOL, $(bench_machine)"
echo "--- FFTW planning (FFTW_MEASURE above 64^3, wisdom cached in $LAMINA_FFTW_WISDOM):"
echo "    a first run at each size and thread count pays it; the runs below reuse it"
for n in $SIZES; do
  for t in 1 2; do
    /usr/bin/time -f "    plan ${n}^3 ${t} thr: %e s" "$BIN" cases/cells/sphere.toml --name plan \
      --library "$LIB" --overwrite --resolution "$n" --threads "$t" --tol 1 --quiet > /dev/null
  done
done
echo "--- sphere (19 %, E 156 MPa / 890 MPa) and polyurea cells, 1 and 2 threads"
for n in $SIZES; do
  for t in 1 2; do
    run sphere cases/cells/sphere.toml "$n" "$t"
    run polyurea cases/cells/polyurea.toml "$n" "$t"
  done
done

echo "--- sphere at tol 1e-4 (C to 5+ digits for this cell, checked below), 2 threads"
for n in $SIZES; do
  TOL=1e-4 run sphere-tol1e-4 cases/cells/sphere.toml "$n" 2
done

echo "--- contrast sweep: sphere inclusion E (matrix 156 MPa), 2 threads"
for E in 1.56e9 15.6e9 156e9; do
  cell="$OUT/sphere-E$E.toml"
  sed "s/^E = 890e6/E = $E/" cases/cells/sphere.toml > "$cell"
  for n in $SIZES; do
    run "sphere-E$E" "$cell" "$n" 2
  done
done

echo "--- resolution study of the sphere cell, 2 threads, tol 1e-8"
STUDY="32 64 128"
[ "${BENCH_256:-0}" = 1 ] && STUDY="32 64 128 256"
for n in $STUDY; do
  if [ "$n" = 256 ]; then  # accuracy only: skip the long FFTW_MEASURE planning
    TOL=1e-8 run study cases/cells/sphere.toml "$n" 2 --fftw-plan estimate
  else
    TOL=1e-8 run study cases/cells/sphere.toml "$n" 2
  fi
done
/usr/bin/python3 - "$RES" <<'PY'
import json, sys, math
rows = [json.loads(l) for l in open(sys.argv[1]) if '"study"' in l]
by = {r["n"]: r for r in rows}
names = {"C11": (0, 0), "C12": (0, 1), "C44": (3, 3)}
for key, (i, j) in names.items():
    vals = {n: by[n]["C"][i][j] for n in by}
    line = "  ".join("%d^3 %.6g" % (n, v) for n, v in sorted(vals.items()))
    if all(n in vals for n in (64, 128, 256)):
        a, b, c = vals[64], vals[128], vals[256]
        p = math.log2(abs((a - b) / (c - b))) if c != b and (a - b) / (b - c) > 0 else 1.0
        ext = c + (c - b) / (2 ** p - 1)
        src = "Richardson 64/128/256, observed order %.2f" % p
    elif all(n in vals for n in (64, 128)):
        a, b = vals[64], vals[128]
        ext = b + (b - a)  # first order
        src = "first-order extrapolation 64/128 (run with BENCH_256=1 for Richardson)"
    else:
        continue
    print("%s: %s -> extrapolated %.6g (%s); 32^3 off by %.2f %%" % (
        key, line, ext, src, 100 * (vals[32] - ext) / ext))
PY
/usr/bin/python3 - "$RES" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
ref = {r["n"]: r["C"] for r in rows if r["case"] == "study"}
print("--- digits: worst relative error of the constants (|C_ij| > 1e-6 max|C|) against tol 1e-8")
for r in rows:
    if r["case"] not in ("sphere", "sphere-tol1e-4") or r["n"] not in ref:
        continue
    C, R = r["C"], ref[r["n"]]
    m = max(abs(x) for row in R for x in row)
    err = max(abs(C[i][j] - R[i][j]) / abs(R[i][j]) for i in range(6) for j in range(6)
              if abs(R[i][j]) > 1e-6 * m)
    print("  %-16s %4d^3 %d thr: %.1e" % (r["case"], r["n"], r["threads"], err))
PY
KERNELS="$BUILD/bin/homogenize_kernels"
if [ -x "$KERNELS" ]; then
  echo "--- one CG iteration against the FFT floor (3 r2c + 3 c2r), 128^3 sphere cell (composite"
  echo "    voxels), 1 thread, FFTW_MEASURE"
  kcell="$OUT/sphere-kernels.toml" # the plain effective C: no size
  grep -v '^size' cases/cells/sphere.toml > "$kcell"
  for prec in single double; do
    echo "  $prec precision transforms:"
    "$KERNELS" 128 1 measure "$prec" "$kcell" | sed 's/^/    /'
  done
fi

if [ -n "${BENCH_BASELINE:-}" ]; then
  PAIRS="${BENCH_PAIRS:-3}" OLD_TOL="${BENCH_OLD_TOL:-1e-3}" NEW_TOL="${BENCH_NEW_TOL:-1e-3}"
  PAIR_THREADS="${BENCH_PAIR_THREADS:-2}" # 2: the FANS comparison's configuration; 1: user CPU is the work
  plain="$OUT/sphere-plain.toml" # the plain effective C: no size, so no dispersion tensor
  grep -v '^size' cases/cells/sphere.toml > "$plain"
  PAIRS_OUT="$OUT/pairs.txt"
  : > "$PAIRS_OUT"
  echo "--- old ($BENCH_BASELINE) against new, 128^3 sphere cell without size, $PAIR_THREADS thread(s)," \
    "$PAIRS alternating pairs, equal accuracy (old tol $OLD_TOL, new $NEW_TOL) and tol 1e-5"
  # pair BIN TOL LABEL: one run, "LABEL wall user" appended to $PAIRS_OUT
  pair() {
    /usr/bin/time -f "$3 %e %U" -a -o "$PAIRS_OUT" "$1" "$plain" --name q --library "$LIB" \
      --overwrite --resolution 128 --threads "$PAIR_THREADS" --tol "$2" --json --quiet > /dev/null
  }
  pair "$BENCH_BASELINE" 1 warm-old # planning and wisdom, not counted
  pair "$BIN" 1 warm-new
  for _ in $(seq "$PAIRS"); do
    pair "$BENCH_BASELINE" "$OLD_TOL" old-equal # ed9714b at 1e-3: the comparison's 7.5 s idle
    pair "$BIN" "$NEW_TOL" new-equal
    pair "$BENCH_BASELINE" 1e-5 old-1e-5
    pair "$BIN" 1e-5 new-1e-5
  done
  echo "  load after: $(bench_machine)"
  /usr/bin/python3 - "$PAIRS_OUT" <<'PY'
import collections, statistics, sys
runs = collections.defaultdict(list)
for line in open(sys.argv[1]):
    label, wall, user = line.split()
    runs[label].append((float(wall), float(user)))
# FANS figures of the FANS comparison (same kind of machine): 27 s at its equal-accuracy
# tol 1e-2, 74 s at 1e-8; lamina ed9714b on the idle machine: 7.5 s at 1e-3,
# 14.0 s at 1e-5
med = lambda label, i: statistics.median(r[i] for r in runs[label])
def show(label):
    return "%-9s wall %s user %s" % (label, [r[0] for r in runs[label]], [r[1] for r in runs[label]])
for label in ("old-equal", "new-equal", "old-1e-5", "new-1e-5"):
    if runs[label]:
        print("  " + show(label))
# (the idle scaling assumes the baseline is ed9714b at BENCH_OLD_TOL 1e-3)
for new, old, idle, fans, what in (("new-equal", "old-equal", 7.5, 27.0, "equal accuracy (decade tolerances)"),
                                   ("new-1e-5", "old-1e-5", 14.0, 74.0, "tol 1e-5")):
    if not runs[new] or not runs[old]:
        continue
    w, u = med(new, 0) / med(old, 0), med(new, 1) / med(old, 1)
    line = "  %s: new/old (medians) wall %.2f, user CPU %.2f" % (what, w, u)
    if idle:
        line += "; x %.1f s (ed9714b idle) = %.1f s, %.2fx FANS's %.0f s (wall ratio), %.2fx (CPU ratio)" % (
            idle, w * idle, w * idle / fans, fans, u * idle / fans)
    print(line)
PY
fi
echo "results: $RES"
