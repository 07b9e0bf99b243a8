# Shared by the benchmark scripts (source it after `cd` to the checkout):
# the binary, the round count, a scratch folder removed on exit, medians and
# wall-clock stamps, the machine line and the do-nothing baseline.
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
