#!/usr/bin/env bash
# Accuracy per second of composite voxels against plain (staircase) voxels
# (not a test): the 19 % sphere cell of cases/cells/sphere.toml without its
# size line, inclusion E at contrast 10 and 1000 to the 156 MPa matrix
# (1.56e9, 156e9 Pa) and a pore (law = "void": contrast infinity), with
# composite_voxels = true and false, at N = 16 24 32 48 64 voxels per edge.
# With the pore both kinds run the same staircase voxels: a voxel cut by a
# pore stays whole (the laminate with a void ply made CG fail to converge
# and C 25 % too soft: docs/homogenize-solver.md, "Pores"), so the pore
# rows give the staircase's accuracy per second and a tie.
#
# Reference per contrast (the converged C11*, C44*): one least-squares fit
# of all runs of both kinds, C(N) = C* + g (f_N - 0.19) + b_kind / N, with
# f_N the inclusion fraction the run reports (the staircase's voxel
# fraction jumps with N; a composite run's sub-voxel fraction is 0.19 to
# 1e-4) and b_kind one first-order term per kind: the fit of
# docs/homogenize.md "Composite voxels" (staircase only there) extended by
# the composite runs. Its standard error is printed: a target error below
# it cannot be judged.
#
# Reported per run: N, kind, CG iterations (max over the six load cases and
# their sum), wall time (the whole process: cell build with its composite
# voxels, FFT plans, solve), C11 and C44 error against the reference. Then
# "accuracy per second": per contrast, target (1 %, 0.1 %) and constant
# (C11, C44), the wall time each kind needs to stay within the target: the
# smallest N from which every larger N of the sweep is within it, with N
# and wall time interpolated log-log between that N and the one before
# (error ~ N^-p, time ~ N^q); "<= t" when the smallest N is already
# within, "> t" when the largest is not. The faster kind wins.
#
# Usage: bash bench/homogenize/composite_accuracy.sh [BUILD_DIR]
# Env: SIZES (default "16 24 32 48 64"), BENCH_TOL (1e-5), BENCH_THREADS (2),
#      CONTRASTS (default "10 1000 void"), BENCH_OUT (default
#      BUILD/bench-composite-accuracy). At least three sizes (the fit has up
#      to four unknowns over two kinds; with fewer the reference is flagged
#      uncertain). Defaults: 30 runs, about 2 minutes on a quiet 2-core
#      machine (estimated, not timed: one CG iteration at 64^3 on 2 threads
#      is about 1/8 of the ~200 ms at 128^3 in bench/homogenize/sphere-128.md,
#      and the costliest run, contrast 1000 with composite voxels at 64^3,
#      takes ~130 iterations per load case, 6 load cases: ~20 s; the cell
#      builds and FFT plans add about a second per run).
set -euo pipefail
source "$(dirname "$0")/common.sh"
bench_setup bench-composite-accuracy "${1:-build}"
SIZES="${SIZES:-16 24 32 48 64}"
TOL="${BENCH_TOL:-1e-5}"
THREADS="${BENCH_THREADS:-2}"
CONTRASTS="${CONTRASTS:-10 1000 void}"
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

echo "composite accuracy bench: sizes $SIZES, tol $TOL, $THREADS threads, $(bench_machine)"
for contrast in $CONTRASTS; do
  for composite in true false; do
    file=$(cell "$contrast" "$composite")
    kind=$([ "$composite" = true ] && echo composite || echo staircase)
    for n in $SIZES; do
      t0=$(date +%s.%N)
      "$BIN" "$file" --name "sphere-$contrast-$kind-$n" --library "$LIB" --overwrite \
        --resolution "$n" --threads "$THREADS" --tol "$TOL" --json --quiet > "$OUT/last.json"
      t1=$(date +%s.%N)
      /usr/bin/python3 - "$OUT/last.json" "$contrast" "$kind" "$n" "$t0" "$t1" >> "$RES" <<'PY'
import json, sys
j = json.loads(open(sys.argv[1]).read().splitlines()[-1])
print(json.dumps({"contrast": sys.argv[2], "kind": sys.argv[3], "n": int(sys.argv[4]),
                  "wall": float(sys.argv[6]) - float(sys.argv[5]), "solve": j["wall_s"],
                  "iterations": j["iterations"], "fraction": j["volume_fraction"],
                  "C11": j["C"][0][0], "C44": j["C"][3][3]}))
PY
    done
  done
done

/usr/bin/python3 - "$RES" <<'PY'
import json, math, sys

runs = [json.loads(line) for line in open(sys.argv[1])]
KINDS = ("composite", "staircase")
TARGETS = (1e-2, 1e-3)


def solve(a, b):
    """Gaussian elimination with partial pivoting: a x = b (small, dense)."""
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        if m[c][c] == 0:
            raise ZeroDivisionError("singular fit")
        for r in range(c + 1, n):
            f = m[r][c] / m[c][c]
            for k in range(c, n + 1):
                m[r][k] -= f * m[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (m[r][n] - sum(m[r][k] * x[k] for k in range(r + 1, n))) / m[r][r]
    return x


def reference(rs, key):
    """C* and its standard error: C = C* + g (f - 0.19) + b_kind / N."""
    kinds = [k for k in KINDS if any(r["kind"] == k for r in rs)]
    series = {k: sorted((r["n"], r["fraction"]) for r in rs if r["kind"] == k) for k in kinds}
    if len(kinds) == 2 and series[kinds[0]] == series[kinds[1]]:
        kinds = kinds[:1]  # the same voxels (pores): one series, one first-order term
        rs = [r for r in rs if r["kind"] == kinds[0]]
    rows = [[1.0, r["fraction"] - 0.19] +
            [1.0 / r["n"] if r["kind"] == k or len(kinds) == 1 else 0.0 for k in kinds]
            for r in rs]
    # the fraction term needs a spread of fractions (a staircase series)
    if max(r[1] for r in rows) - min(r[1] for r in rows) < 1e-6:
        rows = [[r[0]] + r[2:] for r in rows]
    y = [r[key] for r in rs]
    p = len(rows[0])
    ata = [[sum(row[i] * row[j] for row in rows) for j in range(p)] for i in range(p)]
    aty = [sum(row[i] * yi for row, yi in zip(rows, y)) for i in range(p)]
    x = solve(ata, aty)
    res = [yi - sum(c * v for c, v in zip(x, row)) for row, yi in zip(rows, y)]
    dof = len(y) - p
    if dof <= 0:
        return x[0], float("nan")
    s2 = sum(r * r for r in res) / dof
    e0 = [1.0] + [0.0] * (p - 1)
    var0 = solve(ata, e0)[0] * s2  # (A^T A)^-1_00 s^2
    return x[0], math.sqrt(max(var0, 0.0))


def reach(series, target):
    """Wall time to stay within target: (time, text)."""
    series = sorted(series, key=lambda s: s[0])  # (n, err, wall)
    within = [abs(e) <= target for _, e, _ in series]
    if not within[-1]:
        return math.inf, "> %.3g s" % series[-1][2]
    first = len(series) - 1
    while first > 0 and within[first - 1]:
        first -= 1
    if first == 0:
        return series[0][2], "<= %.3g s" % series[0][2]
    (n0, e0, t0), (n1, e1, t1) = series[first - 1], series[first]
    e0, e1 = max(abs(e0), 1e-300), max(abs(e1), 1e-300)
    # log-log: err ~ N^-p between n0 and n1, then time ~ N^q
    s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
    s = min(max(s, 0.0), 1.0)
    t = math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    n = math.exp(math.log(n0) + s * (math.log(n1) - math.log(n0)))
    return t, "%.3g s (N %.0f)" % (t, n)


contrasts = []
for r in runs:
    if r["contrast"] not in contrasts:
        contrasts.append(r["contrast"])
summary = []
print("\nper run: error = (C - C*) / C*, C* the fit of both kinds (see the script's header)")
print("%-8s %-9s %4s %7s %8s %8s %9s %9s %8s" % (
    "contrast", "kind", "N", "f_N", "CG max", "CG sum", "wall s", "C11 err", "C44 err"))
for c in contrasts:
    rs = [r for r in runs if r["contrast"] == c]
    ref = {key: reference(rs, key) for key in ("C11", "C44")}
    for r in rs:
        for key in ("C11", "C44"):
            r[key + "err"] = (r[key] - ref[key][0]) / ref[key][0]
        print("%-8s %-9s %4d %7.5f %8d %8d %9.3f %+8.3f%% %+7.3f%%" % (
            c, r["kind"], r["n"], r["fraction"], max(r["iterations"]), sum(r["iterations"]),
            r["wall"], 100 * r["C11err"], 100 * r["C44err"]))
    print("%-8s reference C11* %.6g Pa (standard error %.2g %%), C44* %.6g Pa (%.2g %%)" % (
        c, ref["C11"][0], 100 * ref["C11"][1] / ref["C11"][0], ref["C44"][0],
        100 * ref["C44"][1] / ref["C44"][0]))
    for key in ("C11", "C44"):
        for target in TARGETS:
            got = {}
            for k in KINDS:
                series = [(r["n"], r[key + "err"], r["wall"]) for r in rs if r["kind"] == k]
                got[k] = reach(series, target) if series else (math.inf, "-")
            tc, ts = got["composite"][0], got["staircase"][0]
            win = ("none" if math.isinf(tc) and math.isinf(ts) else
                   "composite" if tc < ts else "staircase" if ts < tc else "tie")
            voxels = {k: sorted((r["n"], r["fraction"]) for r in rs if r["kind"] == k)
                      for k in KINDS}
            if voxels["composite"] == voxels["staircase"]:
                win = "same voxels (a pore's cut voxels stay whole)"
            elif not ref[key][1] <= 0.3 * target * abs(ref[key][0]):  # NaN: uncertain too
                win += " (reference uncertain)"
            summary.append((c, key, target, got["composite"][1], got["staircase"][1], win))

print("\naccuracy per second: wall time to stay within the target error (interpolated over N)")
print("%-8s %-4s %7s  %-22s %-22s %s" % ("contrast", "C", "target", "composite", "staircase",
                                          "winner"))
for c, key, target, comp, stair, win in summary:
    print("%-8s %-4s %6g%%  %-22s %-22s %s" % (c, key, 100 * target, comp, stair, win))
PY
echo "results: $RES"
