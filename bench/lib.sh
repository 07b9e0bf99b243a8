# shellcheck shell=bash disable=SC2034  # (the variables set here are the sourcing script's)
# Shared by the benchmark scripts (source it after `cd` to the checkout):
# the binary, the round count, a scratch folder removed on exit, medians and
# wall-clock stamps, the machine line, the do-nothing baseline and the GPU
# benchmarks' settings.
bin=${bin:-build/holoray}
ROUNDS=${ROUNDS:-3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The median of the numbers on stdin, one per line.
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# Seconds since the epoch, to the nanosecond.
now() { date +%s.%N; }
# Seconds from stamp $1 to stamp $2.
elapsed() { awk -v a="$1" -v b="$2" 'BEGIN {print b - a}'; }
# "N cores, CPU model": the machine line of every results file.
machine() { echo "$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"; }
# The do-nothing baseline: `holoray --help` (the whole process) ROUNDS
# times; its median, to 3 decimals.
nothing_median() {
  local r t0 t1
  for r in $(seq "$ROUNDS"); do
    t0=$(now); "$bin" --help > /dev/null; t1=$(now)
    elapsed "$t0" "$t1" >> "$tmp/nothing"
  done
  printf %.3f "$(median < "$tmp/nothing")"
}
# Sets BASE_BIN, unless given, to a Release holoray built from commit $1 in
# a scratch worktree, removed (with $tmp) on exit.
build_baseline() {
  [[ -n ${BASE_BIN:-} ]] && return
  git worktree add -f --detach "$tmp/base" "$1" >/dev/null 2>&1
  cmake -S "$tmp/base" -B "$tmp/base/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOLORAY_TESTS=OFF -DHOLORAY_BENCH=OFF >/dev/null
  cmake --build "$tmp/base/build" --target holoray-cli >/dev/null
  BASE_BIN=$tmp/base/build/holoray
  trap 'git worktree remove --force "$tmp/base" >/dev/null 2>&1; rm -rf "$tmp"' EXIT
}
# Builds the benchmark programs named ($2...) into build folder $1, turning
# HOLORAY_BENCH on there (a plain build leaves bench/ out).
bench_targets() {
  local dir=$1
  shift
  cmake -S . -B "$dir" -DHOLORAY_BENCH=ON >/dev/null
  cmake --build "$dir" --target "$@" >/dev/null
}
# The GPU benchmarks' settings (bench/run_gpu_bench.sh, run_gpu_knobs.sh),
# from the environment: shared (the scenes' folder), frames_bin, device,
# frames, warmup and lenses (240x135, the issue's 3840x2160 EIA; QUICK=1: a
# check at 30x17 lenses, 2 frames after 1); build/bench/holoray_gpu_frames
# built unless FRAMES_BIN names one. Exits 1, naming the script $1, when the
# scenes or the binary are missing.
gpu_bench_settings() {
  shared=${HOLORAY_SHARED:-../shared}
  frames_bin=${FRAMES_BIN:-build/bench/holoray_gpu_frames}
  device=${DEVICE:-gpu}
  frames=${FRAMES:-20}
  warmup=${WARMUP:-3}
  lenses=240x135
  if [[ -n ${QUICK:-} ]]; then lenses=30x17 frames=2 warmup=1; fi
  [[ -d $shared/scenes/nff ]] || { echo "$1: needs $shared/scenes" >&2; exit 1; }
  [[ -n ${FRAMES_BIN:-} ]] || bench_targets build holoray_gpu_frames
  [[ -x $frames_bin ]] || { echo "$1: $frames_bin is missing" >&2; exit 1; }
}
