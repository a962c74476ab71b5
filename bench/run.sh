#!/usr/bin/env bash
# Runs every stage's benchmark (by hand, not part of `make test`).
# Usage: bash bench/run.sh [BUILD_DIR]   (make bench does this)
set -euo pipefail
BUILD="${1:-build}"
cd "$(dirname "$0")/.."
for stage in homogenize membrane; do
  if [ -x "bench/$stage/run.sh" ] || [ -f "bench/$stage/run.sh" ]; then
    echo "=== bench: $stage ==="
    bash "bench/$stage/run.sh" "$BUILD"
  fi
done
