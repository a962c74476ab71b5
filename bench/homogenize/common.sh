# Shared preamble of the homogenize benchmarks (sourced by run.sh and
# nonlinear.sh, not run on its own).
# bench_setup OUT_NAME [BUILD_DIR]: sets BUILD (default build), moves to the
# repository root, sets BIN (BUILD/bin/homogenize, which must exist) and
# OUT (BENCH_OUT, else BUILD/OUT_NAME; created).
bench_setup() {
  BUILD="${2:-build}"
  cd "$(dirname "${BASH_SOURCE[0]}")/../.."
  BIN="$BUILD/bin/homogenize"
  [ -x "$BIN" ] || { echo "build $BIN first" >&2; exit 1; }
  OUT="${BENCH_OUT:-$BUILD/$1}"
  mkdir -p "$OUT"
}

# bench_machine: cores, load average and UTC time, for the first line of a report
bench_machine() {
  echo "$(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)"
}
