#!/usr/bin/env bash
# Cost of the .msh structural check (membrane/io/msh_check.hpp) that
# readGmsh runs before gmsh's reader: meshes cases/meshes/square.geo with
# element size CLMAX (default 2e-4 m: about 290,000 nodes, 30 MB files) in
# MSH 4.1 and 2.2, ASCII and binary, and runs membrane_msh_check on each
# (best and median of REPS checks, from memory and from the file).
# The machine may be shared: compare against a baseline binary in the same
# session, alternating the runs.
# Usage: bash bench/membrane/msh_check.sh [BUILD_DIR]   env: CLMAX=2e-4 REPS=5
set -euo pipefail
BUILD="${1:-build}"
cd "$(dirname "$0")/../.."
CLMAX="${CLMAX:-2e-4}"
REPS="${REPS:-5}"
OUT="$(mktemp -d /tmp/lamina-bench-msh.XXXXXX)"
trap 'rm -rf "$OUT"' EXIT
echo "msh check bench: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), clmax $CLMAX"
for format in msh41 msh22; do
  for bin in "" "-bin"; do
    file="$OUT/square-$format$bin.msh"
    gmsh -2 -clmax "$CLMAX" -format "$format" $bin cases/meshes/square.geo -o "$file" > /dev/null
    "$BUILD/bin/membrane_msh_check" "$file" "$REPS"
  done
done
