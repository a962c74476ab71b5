#!/usr/bin/env bash
# The end-to-end demo (`make demo`): unit cells homogenized into a library,
# layered fabrics built from a ply, membranes of those materials struck, with
# pictures and a one-screen summary per run; the drag paper's blast-loaded
# roof, which runs from the start on the second core; last, the
# rate-dependent pipeline: the two-scale polyurea cell made a reduced-order
# law, and a polyurea sheet struck by a projectile with three laws (elastic,
# GVBO, reduced-order cell), its projectile velocity plotted.
#   bash scripts/demo.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
BUILD="$(cd "${1:-build}" && pwd)"
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OUT="$(mkdir -p "${2:-$ROOT/demo-out}" && cd "${2:-$ROOT/demo-out}" && pwd)"
BIN="$BUILD/bin"
PY=/usr/bin/python3
LIB="$OUT/library.toml"
cd "$ROOT"
rm -rf "$OUT/runs" "$OUT/cells" "$OUT/impact" "$LIB" "$LIB.lock" "$OUT/library.side"
mkdir -p "$OUT/runs" "$OUT/cells" "$OUT/materials" "$OUT/impact"
start=$(date +%s)

step() { printf '\n== %s\n' "$*"; }
membrane_run() { # membrane_run DIR CASE MATERIAL [extra --set ...]: its log in DIR/run.log
  local dir="$1" case="$2" material="$3"
  shift 3
  mkdir -p "$dir"
  if ! "$BIN/membrane" run "$case" --library "$LIB" --out "$dir" \
    --set "section[0].material=$material" "$@" > /dev/null 2> "$dir/run.log"; then
    cat "$dir/run.log" >&2
    exit 1
  fi
}

# The roof (step 4) is small (one thread) and the longest run: it starts now
# on the second core; steps 1 to 3, then the sheets of step 5, share the first.
mkdir -p "$OUT/roof"
"$BIN/membrane" run cases/membrane/blast-roof.toml --out "$OUT/roof" > /dev/null 2> "$OUT/roof.log" &
ROOF_PID=$!
trap 'kill "$ROOF_PID" 2> /dev/null || true' EXIT

step "1. Homogenize the polyurea cell (45-degree hard ellipsoids, 19 %, GVBO soft matrix)"
"$BIN/micro" cases/cells/polyurea.toml --out "$OUT/cells/polyurea-phases.h5"
"$PY" scripts/plot_cell.py "$OUT/cells/polyurea-phases.h5" "$OUT/cells/polyurea-cell.png" \
  "polyurea cell: hard ellipsoids (19 %) at 45 degrees from z"
"$BIN/homogenize" cases/cells/polyurea.toml --library "$LIB" --name polyurea-45 --json \
  > "$OUT/cells/polyurea-45.json"
step "   and an E-glass fibre cell (50 % fibres along x in the same matrix) for a fabric ply"
"$BIN/homogenize" cases/cells/fiber.toml --library "$LIB" --name glass-ply --json \
  > "$OUT/cells/glass-ply.json"

step "2. Layered fabrics from the ply: [0/90] and [0/45/90/-45], 0.25 mm plies"
"$BIN/materials" --library "$LIB" layup fabric-0-90 \
  --ply glass-ply:0:0.25e-3 --ply glass-ply:90:0.25e-3
"$BIN/materials" --library "$LIB" layup fabric-quasi \
  --ply glass-ply:0:0.25e-3 --ply glass-ply:45:0.25e-3 \
  --ply glass-ply:90:0.25e-3 --ply glass-ply:-45:0.25e-3
"$BIN/materials" --library "$LIB" add table1-anisotropic --from-catalog table1-anisotropic
"$BIN/materials" --library "$LIB" list

step "3. Impacts: membranes of each material, and the paper's Table 1 impact"
run() { # run NAME CASE MATERIAL [extra --set ...]
  local name="$1" case="$2" material="$3"
  shift 3
  local dir="$OUT/runs/$name"
  "$BIN/materials" --library "$LIB" show "$material" --json > "$OUT/materials/$material.json"
  membrane_run "$dir" "$case" "$material" "$@"
  "$PY" scripts/plot_run.py "$dir" --title "$name ($material)"
  "$PY" scripts/summarize_run.py "$dir" "$OUT/materials/$material.json" --title "$name"
}
run polyurea-circle cases/demo/circle-impact.toml polyurea-45
run fabric-0-90-square cases/demo/square-impact.toml fabric-0-90
run fabric-quasi-square cases/demo/square-impact.toml fabric-quasi
run table1-paper cases/membrane/table1-anisotropic.toml table1-anisotropic

# The rate-dependent sheets (step 5) start now on the first core, beside the
# roof: the reduced-order cell, then the three impacts (their log: impact.log).
impact() { # impact DIR MATERIAL
  membrane_run "$OUT/impact/$1" cases/membrane/polyurea-sheet-impact.toml "$2"
}
(
  set -e
  "$BIN/homogenize" cases/cells/polyurea-two-scale.toml --library "$LIB" --name pu-rom \
    --reduced-order --scheme clustering --quiet
  impact elastic polyurea-elastic-rest
  impact gvbo polyurea-gvbo
  impact reduced-order pu-rom
) > "$OUT/impact.log" 2>&1 &
SHEETS_PID=$!
trap 'kill "$ROOF_PID" "$SHEETS_PID" 2> /dev/null || true' EXIT

step "4. The blast-loaded fabric roof of the drag paper (section 5), with and without drag"
printf '   (run on the second core since the start: 1,360 elements, one thread)\n'
if ! wait "$ROOF_PID"; then
  cat "$OUT/roof.log" >&2
  exit 1
fi
"$PY" scripts/plot_roof.py "$OUT/roof"

step "5. Rate-dependent polyurea: the two-scale cell (Table 11) as a reduced-order law, and a"
printf '   polyurea sheet struck at 100 m/s with three laws: elastic, GVBO (Table 5), the cell\n'
if ! wait "$SHEETS_PID"; then
  cat "$OUT/impact.log" >&2
  exit 1
fi
trap - EXIT
"$PY" scripts/plot_impact.py "$OUT/impact/elastic" "$OUT/impact/gvbo" "$OUT/impact/reduced-order" \
  --label "elastic (rest moduli)" --label "GVBO (Table 5)" --label "two-scale cell (Table 11)" \
  --out "$OUT/impact/impact-velocity.png"

step "6. Results"
printf '  %-24s %s\n' cells "$(cd "$OUT/cells" && ls | tr '\n' ' ')"
for d in "$OUT"/runs/*/; do
  printf '  %-24s %s\n' "$(basename "$d")" "$(cd "$d" && ls *.xdmf speed.png probes.png summary.txt | tr '\n' ' ')"
done
printf '  %-24s %s\n' roof "roof-side.png roof-history.png summary.json (with-drag/, without-drag/)"
printf '  %-24s %s\n' impact "impact-velocity.png (elastic/, gvbo/, reduced-order/)"
printf '\nlamina demo done in %ss. Everything is under:\n  %s\n' "$(( $(date +%s) - start ))" "$OUT"
printf 'Open a run in ParaView: paraview %s/runs/table1-paper/table1-anisotropic.xdmf\n' "$OUT"
