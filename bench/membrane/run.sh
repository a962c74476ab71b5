#!/usr/bin/env bash
# Membrane benchmark (Newmark and explicit steps) on two meshes of about the
# same size: structured N x N squares (2 triangles each; bench.toml, tau =
# 0.4 h_el / c_S) and the unstructured gmsh square of cases/meshes/square.geo
# (L = 1 m, element size LC; bench-gmsh.toml, tau = 4.3e-6 s), both isotropic
# E = 1 GPa, nu = 0.3, rho = 1000, h = 1 mm, fixed edges, centre strike at
# 1 m/s, STEPS steps (default 200).
# 1. `membrane run` end to end: assembly, set-up and per-step times, CG
#    iterations and peak memory for 1 and 2 threads, and (structured N <= 300,
#    and the unstructured square) the largest difference of the probe
#    histories between the CG run and the factorized (CHOLMOD) solve.
# 2. membrane_kernels (bench/membrane/kernels.cpp) at KERNEL_SIZES and on the
#    unstructured square, 1 and 2 threads: one product with K in each storage
#    (the 3x3-block one is the memory floor of a step), the Newmark step, one
#    CG iteration and the explicit steps against it; best and median wall and
#    CPU per call.
# 3. A summary of the targets from this run's figures (best wall for the
#    kernels, mean step for `membrane run`): unstructured / structured Newmark
#    step (the largest structured N <= 300, same threads), CG iteration /
#    floor, explicit fabric step unstructured / structured and / floor, and
#    the 2-thread speed-up of each step on each mesh.
# 4. bench/membrane/gvbo.sh at GVBO_SIZES: the explicit step of a GVBO
#    polyurea sheet against the same sheet elastic, 1 and 2 threads.
# The machine may be shared: compare against a baseline run in the same
# session (alternate the binaries), not against old figures.
# Usage: bash bench/membrane/run.sh [BUILD_DIR]
#   env: SIZES="100 300 800" STEPS=200 KERNEL_SIZES="300" KERNEL_STEPS=40
#        LC=0.00352 (187,762 triangles; 0.01: about 23,000) GVBO_SIZES="300"
#        GVBO_STEPS=20; BENCH_QUICK=1: the defaults become SIZES=100,
#        KERNEL_SIZES=100, LC=0.01, GVBO_SIZES=100 (meshes of about 20,000
#        triangles; a variable set explicitly wins)
set -euo pipefail
BUILD="${1:-build}"
cd "$(dirname "$0")/../.."
BIN="$BUILD/bin/membrane"
KERNELS="$BUILD/bin/membrane_kernels"
if [ "${BENCH_QUICK:-0}" = 1 ]; then
  SIZES="${SIZES:-100}" KERNEL_SIZES="${KERNEL_SIZES:-100}" LC="${LC:-0.01}"
  GVBO_SIZES="${GVBO_SIZES:-100}"
fi
SIZES="${SIZES:-100 300 800}"
STEPS="${STEPS:-200}"
KERNEL_SIZES="${KERNEL_SIZES:-300}"
KERNEL_STEPS="${KERNEL_STEPS:-40}"
LC="${LC:-0.00352}"
OUT="$(mktemp -d /tmp/lamina-bench-membrane.XXXXXX)"
LIB="$OUT/empty-library.toml"   # inline material: never touch the user's library
MSH="$OUT/square-bench.msh"
trap 'rm -rf "$OUT"' EXIT

run() { # name threads case label extra-args...: one `membrane run`, its line
  local name=$1 th=$2 case=$3 label=$4; shift 4
  OMP_NUM_THREADS=$th /usr/bin/time -f "%M" -o "$OUT/$name.mem" "$BIN" run "$case" \
    --out "$OUT/$name" --library "$LIB" --json "$@" > "$OUT/$name.json"
  python3 - "$OUT/$name.json" "$OUT/$name.mem" "$label" "$th" "$name" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); mem = int(open(sys.argv[2]).read().split()[-1]) / 1024
print("%-14s %-6s threads=%s dofs=%-8d assembly=%.3f s  setup=%.3f s  step=%.2f ms  iters=%.1f  peak=%.0f MB"
      % (sys.argv[5], sys.argv[3], sys.argv[4], d["dofs"], d["assembly_s"], d["factor_s"],
         1e3 * d["step_s"], d["solver"]["mean_iterations"], mem))
PY
}

structured() { # name threads N extra-args...: bench.toml at N x N, dt = 0.4 h_el / c_S
  local name=$1 th=$2 n=$3; shift 3
  local dt te
  dt=$(python3 -c "import math; c=math.sqrt(1e9/(2*1.3)/1000); print(repr(0.4/$n/c))")
  te=$(python3 -c "print(repr($STEPS*$dt))")
  run "$name" "$th" bench/membrane/bench.toml "N=$n" --set mesh.nx="$n" --set time.dt="$dt" \
    --set time.t_end="$te" "$@"
}

unstructured() { # name threads extra-args...: bench-gmsh.toml on $MSH, its tau
  local name=$1 th=$2; shift 2
  local te
  te=$(python3 -c "print(repr($STEPS*4.3e-6))")
  run "$name" "$th" bench/membrane/bench-gmsh.toml "gmsh" --set "mesh.file=\"$MSH\"" \
    --set time.t_end="$te" "$@"
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

kernels() { # name mesh-arg threads: membrane_kernels, its text and $OUT/$name.kernels.json
  echo "--- kernels $2 threads=$3 (load $(cut -d' ' -f1-3 /proc/loadavg))"
  OMP_NUM_THREADS=$3 "$KERNELS" "$2" "$3" "$KERNEL_STEPS" --json "$OUT/$1.kernels.json"
}

echo "membrane bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), steps $STEPS"
for n in $SIZES; do
  for th in 1 2; do structured "cg-$n-$th" "$th" "$n"; done
  if [ "$n" -le 300 ]; then
    structured "chol-$n" 1 "$n" --set solver.type='"cholesky"'
    compare "chol-$n" "cg-$n-1"
  fi
done
echo "unstructured square: gmsh -2 -setnumber L 1 -setnumber lc $LC cases/meshes/square.geo"
gmsh -2 -setnumber L 1 -setnumber lc "$LC" cases/meshes/square.geo -o "$MSH" > "$OUT/gmsh.log" 2>&1 \
  || { cat "$OUT/gmsh.log" >&2; exit 1; }
for th in 1 2; do unstructured "cg-gmsh-$th" "$th"; done
unstructured chol-gmsh 1 --set solver.type='"cholesky"'
compare chol-gmsh cg-gmsh-1
if [ -x "$KERNELS" ]; then
  for n in $KERNEL_SIZES; do
    for th in 1 2; do kernels "kernels-$n-$th" "$n" "$th"; done
  done
  for th in 1 2; do kernels "kernels-gmsh-$th" "$MSH" "$th"; done
  python3 bench/membrane/summary.py "$OUT" "$SIZES" "$KERNEL_SIZES"
else
  echo "run.sh: $KERNELS not found (cmake --build $BUILD --target membrane_kernels):" \
    "no kernels, no summary" >&2
fi
SIZES="${GVBO_SIZES:-300}" STEPS="${GVBO_STEPS:-20}" bash bench/membrane/gvbo.sh "$BUILD"
