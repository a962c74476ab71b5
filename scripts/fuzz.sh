#!/usr/bin/env bash
# Runs every libFuzzer target of BUILD/fuzz for SECONDS each on a corpus
# seeded from cases/ (and fuzz/seeds/); the corpus grows in BUILD/corpus and
# is kept between runs. A crash, an abort, a sanitizer report or a leak
# stops the script with the reproducer in BUILD/fuzz-artifacts/.
#   [FUZZ_TARGETS="case cell ..."] [FUZZ_SEED=N] [FUZZ_RUNS="case=N cell=N ..."] \
#     scripts/fuzz.sh [BUILD] [SECONDS]
# FUZZ_SEED (default 0) is libFuzzer's -seed: 0 lets it pick one (exploring),
# another value repeats the same mutations on the same corpus (CI: a run that
# passed here passes there). FUZZ_RUNS caps the inputs per target (-runs), so
# that a seeded run is the same sequence on a faster machine.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build-fuzz}
SECONDS_EACH=${2:-60}
SEED=${FUZZ_SEED:-0}
runs_of() { # runs_of TARGET: the cap FUZZ_RUNS gives TARGET, or -1 (none)
  local item
  for item in ${FUZZ_RUNS:-}; do
    if [ "${item%%=*}" = "$1" ]; then
      echo "${item#*=}"
      return
    fi
  done
  echo -1
}
corpus=$BUILD/corpus
artifacts=$BUILD/fuzz-artifacts
mkdir -p "$artifacts"
seed() { # seed TARGET FILES...
  local dir=$corpus/$1
  shift
  mkdir -p "$dir"
  for f in "$@"; do cp -n "$f" "$dir/$(basename "$f")" 2>/dev/null || true; done
}
shopt -s nullglob
seed case cases/membrane/*.toml cases/demo/*.toml fuzz/seeds/case/*
seed cell cases/cells/*.toml fuzz/seeds/cell/*
seed catalog materials/catalog.toml fuzz/seeds/catalog/*
seed library fuzz/seeds/library/*
seed msh fuzz/seeds/msh/*
seed args fuzz/seeds/args/*
seed image fuzz/seeds/image/* # first byte: the format (image_fuzzer.cpp)
seed checkpoint fuzz/seeds/checkpoint/* # byte 0: the case and the edit (checkpoint_fuzzer.cpp)
mkdir -p "$corpus/msh"
for geo in cases/meshes/*.geo; do # .msh seeds meshed from the .geo files
  out=$corpus/msh/$(basename "${geo%.geo}").msh
  [ -f "$out" ] || gmsh -2 -format msh41 "$geo" -o "$out" > /dev/null
done
status=0
for target in ${FUZZ_TARGETS:-case cell catalog library msh args image checkpoint}; do
  runs=$(runs_of "$target")
  echo "fuzz: $target for ${SECONDS_EACH} s (seed $SEED, runs $runs)" >&2
  asan=${ASAN_OPTIONS:-}
  # HDF5 has no frame pointers: unwind fully so that lsan.supp's HDF5 entry
  # (a frame inside HDF5) can match (the targets that read HDF5 files)
  case $target in image | checkpoint) asan="${asan:+$asan:}fast_unwind_on_malloc=0" ;; esac
  if ! ASAN_OPTIONS=$asan "$BUILD/fuzz/${target}_fuzzer" "$corpus/$target" -max_total_time="$SECONDS_EACH" \
      -seed="$SEED" -runs="$runs" -reload=0 \
      -timeout=25 -rss_limit_mb=3072 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$artifacts/${target}-" > "$BUILD/fuzz-$target.log" 2>&1; then
    status=1
    echo "fuzz: $target FAILED; log $BUILD/fuzz-$target.log" >&2
    tail -40 "$BUILD/fuzz-$target.log" >&2
    repro=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$BUILD/fuzz-$target.log" | tail -1)
    if [ -n "$repro" ]; then
      echo "fuzz: $target reproducer: $repro (rerun: $BUILD/fuzz/${target}_fuzzer $repro)" >&2
    else
      echo "fuzz: $target stopped without a reproducer file (see the log)" >&2
    fi
  else
    grep -E "^stat::number_of_executed_units|^#[0-9]+.*DONE" "$BUILD/fuzz-$target.log" >&2 || true
  fi
done
exit $status
