#!/usr/bin/env bash
# Accuracy per cost of composite voxels against plain (staircase) voxels
# (not a test): the 19 % sphere cell of cases/cells/sphere.toml without its
# size line, inclusion E at contrast 10, 100, 316 and 1000 to the 156 MPa
# matrix and a pore (law = "void": contrast infinity), with
# composite_voxels = true and false, at N = 16 24 32 48 64 voxels per edge.
# With the pore both kinds run the same staircase voxels: a voxel cut by a
# pore stays whole (the laminate with a void ply made CG fail to converge
# and C 25 % too soft: docs/homogenize-solver.md, "Pores"), so the pore
# rows give the staircase's accuracy only.
#
# Reference per contrast (the converged C11*, C44*): a composite run at
# REF_N (128; other values only for the pore) voxels, tol REF_TOL (1e-7), and Richardson extrapolation of
# the composite runs at 32^3, 64^3 and REF_N^3 with their observed order
# (the composite series converges monotonically; the staircase's error
# jumps with its voxel fraction). For the pore: the staircase run at REF_N
# itself (no extrapolation: its error is that of one staircase run).
#
# Cost: CG iterations summed over the six load cases times voxels, in units
# of one iteration of each load case at 32^3 (a whole 32^3 solve at
# contrast 10, 78 iterations in all, is 13): one iteration
# costs the same per voxel for both kinds, and unlike wall time on a shared
# machine it does not depend on the load. Wall time (the whole process) is
# printed too. Then per contrast the cost each kind needs to be within 2 %,
# 1 % and 0.5 % on C44 and 0.1 % on C11 at that N and every finer N of the
# sweep ("-": not by the largest N).
#
# Usage: bash bench/homogenize/composite_accuracy.sh [BUILD_DIR]
# Env: SIZES (default "16 24 32 48 64"; needs 32 and 64), BENCH_TOL (1e-5),
#      BENCH_THREADS (2), CONTRASTS (default "10 100 316 1000 void"),
#      REF_N (128), REF_TOL (1e-7), BENCH_OUT (default
#      BUILD/bench-composite-accuracy). About 40 minutes with the defaults on
#      a loaded machine (2026-12-03, load 4-18), most of it the 128^3
#      references (875 s at contrast 1000).
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-composite-accuracy "${1:-build}"
SIZES="${SIZES:-16 24 32 48 64}"
TOL="${BENCH_TOL:-1e-5}"
THREADS="${BENCH_THREADS:-2}"
CONTRASTS="${CONTRASTS:-10 100 316 1000 void}"
REF_N="${REF_N:-128}"
REF_TOL="${REF_TOL:-1e-7}"
LIB="$OUT/library.toml"
RES="$OUT/results.jsonl"
rm -f "$LIB" "$LIB.lock"
: > "$RES"
export LAMINA_FFTW_WISDOM="$OUT/fftw-wisdom"

# cell CONTRAST COMPOSITE: writes the cell file and prints its path
cell() {
  local file="$OUT/sphere-$1-$2.toml"
  /usr/bin/python3 - cases/cells/sphere.toml "$1" "$2" > "$file" <<'PY'
import re, sys
text, contrast, composite = open(sys.argv[1]).read(), sys.argv[2], sys.argv[3]
text = re.sub(r"(?m)^size = .*\n", "", text)  # scale-free: no dispersion tensor
text = text.replace("[cell]\n", "[cell]\ncomposite_voxels = %s\n" % composite, 1)
head, name, sphere = text.partition('name = "sphere"\n')
assert name, "cases/cells/sphere.toml: no phase named sphere"
phase, groups, rest = sphere.partition("\n[[inclusions]]")
if contrast == "void":
    phase = 'law = "void"\n'
else:
    phase = re.sub(r"(?m)^E = .*$", "E = %.6g" % (156e6 * float(contrast)), phase)
print(head + name + phase + groups + rest, end="")
PY
  echo "$file"
}

# one N TOL FILE CONTRAST KIND: one homogenization, one JSON line in $RES
one() {
  local n=$1 tol=$2 file=$3 contrast=$4 kind=$5
  local t0 t1
  t0=$(date +%s.%N)
  "$BIN" "$file" --name "sphere-$contrast-$kind-$n" --library "$LIB" --overwrite \
    --resolution "$n" --threads "$THREADS" --tol "$tol" --json --quiet > "$OUT/last.json"
  t1=$(date +%s.%N)
  /usr/bin/python3 - "$OUT/last.json" "$contrast" "$kind" "$n" "$t0" "$t1" >> "$RES" <<'PY'
import json, sys
j = json.loads(open(sys.argv[1]).read().splitlines()[-1])
print(json.dumps({"contrast": sys.argv[2], "kind": sys.argv[3], "n": int(sys.argv[4]),
                  "wall": float(sys.argv[6]) - float(sys.argv[5]), "solve": j["wall_s"],
                  "iterations": j["iterations"], "fraction": j["volume_fraction"],
                  "C11": j["C"][0][0], "C44": j["C"][3][3]}))
PY
}

echo "composite accuracy bench: sizes $SIZES, tol $TOL, reference $REF_N^3 tol $REF_TOL, $THREADS threads, $(bench_machine)"
for contrast in $CONTRASTS; do
  for composite in true false; do
    file=$(cell "$contrast" "$composite")
    kind=$([ "$composite" = true ] && echo composite || echo staircase)
    for n in $SIZES; do
      one "$n" "$TOL" "$file" "$contrast" "$kind"
    done
  done
  one "$REF_N" "$REF_TOL" "$(cell "$contrast" true)" "$contrast" reference
done

/usr/bin/python3 - "$RES" <<'PY'
import json, math, sys

runs = [json.loads(line) for line in open(sys.argv[1])]
UNIT = 6 * 32 ** 3  # one CG iteration of each of the six load cases at 32^3
TARGETS = (("C44", 0.02), ("C44", 0.01), ("C44", 0.005), ("C11", 0.001))


def reference(rs, key):
    """Richardson over the composite 32^3, 64^3 and reference runs (pore: the reference run)."""
    ref = [r for r in rs if r["kind"] == "reference"][0]
    comp = {r["n"]: r[key] for r in rs if r["kind"] == "composite"}
    if rs[0]["contrast"] == "void":
        return ref[key], "the %d^3 run" % ref["n"]
    a, b, c = comp[32], comp[64], ref[key]
    assert ref["n"] == 128, "Richardson over 32, 64, 128: REF_N must be 128"
    order = math.log2(abs((a - b) / (b - c)))
    return c - (b - c) / (2.0 ** order - 1.0), "order %.2f" % order


def cost(r):
    return sum(r["iterations"]) * r["n"] ** 3 / UNIT


def reach(rs, key, target):
    """Cost at the smallest N from which every finer N is within target."""
    rs = sorted(rs, key=lambda r: r["n"])
    ok = [abs(r[key + "err"]) <= target for r in rs]
    for i in range(len(rs)):
        if all(ok[i:]):
            return "%.0f (%d^3)" % (cost(rs[i]), rs[i]["n"])
    return "-"


contrasts = []
for r in runs:
    if r["contrast"] not in contrasts:
        contrasts.append(r["contrast"])
table = []
print("\nper run: error = (C - C*) / C*; cost = iterations x voxels / (6 x 32^3)")
print("%-8s %-9s %4s %7s %8s %8s %9s %9s %9s" % (
    "contrast", "kind", "N", "f_N", "CG sum", "cost", "wall s", "C11 err", "C44 err"))
for c in contrasts:
    rs = [r for r in runs if r["contrast"] == c]
    ref = {key: reference(rs, key) for key in ("C11", "C44")}
    for r in rs:
        for key in ("C11", "C44"):
            r[key + "err"] = (r[key] - ref[key][0]) / ref[key][0]
        print("%-8s %-9s %4d %7.5f %8d %8.1f %9.2f %+8.3f%% %+8.3f%%" % (
            c, r["kind"], r["n"], r["fraction"], sum(r["iterations"]), cost(r), r["wall"],
            100 * r["C11err"], 100 * r["C44err"]))
    print("%-8s C11* %.6g Pa (%s), C44* %.6g Pa (%s)" % (
        c, ref["C11"][0], ref["C11"][1], ref["C44"][0], ref["C44"][1]))
    row = [c]
    for key, target in TARGETS:
        got = [reach([r for r in rs if r["kind"] == k], key, target)
               for k in ("staircase", "composite")]
        row.append(" / ".join(got))
    table.append(row)

print("\ncost to stay within the target (staircase / composite), at that N and every finer N")
print("| contrast | " + " | ".join("%s %g %%" % (k, 100 * t) for k, t in TARGETS) + " |")
for row in table:
    print("| " + " | ".join(row) + " |")
PY
echo "results: $RES"
