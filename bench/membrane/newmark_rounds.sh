#!/usr/bin/env bash
# Alternates two builds on the two Newmark benchmark runs of run.sh (the
# structured 300 x 300 of bench.toml and the unstructured square of
# bench-gmsh.toml, 200 steps each), one thread pinned to CPU 1 and two
# threads on CPUs 0 and 1, and prints the mean step (summary's step_s) and
# the CG iterations per step of each run, with the load.
# Usage: bash bench/membrane/newmark_rounds.sh BASE_BUILD NEW_BUILD [ROUNDS] [OUT]
#   ROUNDS default 3; OUT (default a temporary folder) keeps the outputs,
#   OUT/<base|new>-<s|u>-<threads>, for comparing the builds' probes.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
base=$(cd "$1" && pwd)
new=$(cd "$2" && pwd)
rounds=${3:-3}
out=${4:-$(mktemp -d /tmp/lamina-rounds.XXXXXX)}
mkdir -p "$out"
mesh="$out/square-bench.msh"
[ -f "$mesh" ] || gmsh -2 -setnumber L 1 -setnumber lc 0.00352 "$root/cases/meshes/square.geo" \
  -o "$mesh" > /dev/null
: > "$out/empty.toml" # an empty library: the runs read none
py=/usr/bin/python3
dt=$($py -c "import math; print(repr(0.4/300/math.sqrt(1e9/2.6/1000)))")
te=$($py -c "print(repr(200*$dt))")
tg=$($py -c "print(repr(200*4.3e-6))")
step() { $py -c "import json,sys; d=json.load(sys.stdin); print('%.2f ms, %.1f its' % (d['step_s']*1e3, d['solver']['mean_iterations']))"; }
for r in $(seq "$rounds"); do
  for b in base new; do
    if [ $b = base ]; then bin=$base/bin/membrane; else bin=$new/bin/membrane; fi
    for t in 1 2; do
      if [ $t = 1 ]; then cpus=1; else cpus=0,1; fi
      s=$(cd "$root" && OMP_NUM_THREADS=$t taskset -c $cpus "$bin" run bench/membrane/bench.toml \
        --out "$out/$b-s-$t" --library "$out/empty.toml" --json --set mesh.nx=300 \
        --set time.dt="$dt" --set time.t_end="$te" | step)
      u=$(cd "$root" && OMP_NUM_THREADS=$t taskset -c $cpus "$bin" run bench/membrane/bench-gmsh.toml \
        --out "$out/$b-u-$t" --library "$out/empty.toml" --json --set "mesh.file=\"$mesh\"" \
        --set time.t_end="$tg" | step)
      echo "round $r $b threads=$t structured $s unstructured $u load $(cut -d' ' -f1 /proc/loadavg) $(date -u +%H:%M:%S)"
    done
  done
done
