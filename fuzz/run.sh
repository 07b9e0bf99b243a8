#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, AddressSanitizer + UBSan) into
# build-fuzz/ and runs each for FUZZ_SECONDS seconds (default 60), as many at
# once as there are cores, seeded from the repository's scenes and shots, the
# saved regressions and, when it is there, ../shared/scenes. Fails when a
# target finds a problem and says where the input is: add it to
# fuzz/regressions/<target>/ with the fix, and the test suite
# (FuzzRegressions) replays it on every build from then on.
# Usage: bash fuzz/run.sh [target...]   (targets: nff tachyon shot camera_path display gltf)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-60}
targets=("$@")
((${#targets[@]})) || targets=(nff tachyon shot camera_path display gltf)

command -v clang++ >/dev/null || { echo "fuzz/run.sh: clang++ not found (bash scripts/setup.sh installs it)" >&2; exit 1; }
cmake -S fuzz -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz

shared=../shared/scenes
shopt -s nullglob
seeds() {  # the seed files of one target, small ones only (the fuzzer cuts inputs at -max_len anyway)
  local files=()
  case $1 in
    nff) files=(examples/*.nff "$shared"/nff/*.nff) ;;
    tachyon) files=(tests/data/tachyon/*.dat "$shared"/tachyon/*.dat) ;;
    shot) files=(bench/shots/*.toml tests/data/*.toml) ;;
    camera_path) files=("$shared"/tachyon/*.cam) ;;
    display) files=(examples/displays/*.toml) ;;
    gltf) files=(examples/*.gltf tests/data/blender/*.gltf) ;;
  esac
  files+=(fuzz/regressions/"$1"/*)
  for f in "${files[@]}"; do
    if [ "$(stat -c %s "$f")" -le 65536 ]; then echo "$f"; fi
  done
}

# One target's run: its corpus seeded, then libFuzzer for $seconds, its log in
# build-fuzz/fuzz_<target>.log. Returns 1 on a finding, after saying where it is.
fuzz_one() {
  local t=$1 corpus=build-fuzz/corpus/$1 findings=build-fuzz/findings/$1 extra=() asan=${ASAN_OPTIONS:-}
  mkdir -p "$corpus" "$findings"
  seeds "$t" | while read -r f; do cp "$f" "$corpus/"; done
  echo "== fuzz_$t: ${seconds}s, $(find "$corpus" -type f | wc -l) inputs in the corpus"
  # Debian's assimp 5.2 leaks a few hundred bytes reading valid glTF files
  # (examples/swinging_box.gltf among them): leaks are not looked for there.
  if [ "$t" = gltf ]; then extra=(-detect_leaks=0); asan="detect_leaks=0${asan:+:$asan}"; fi
  if ! ASAN_OPTIONS=$asan build-fuzz/fuzz_"$t" "$corpus" -dict=fuzz/dicts/"$t".dict -max_total_time="$seconds" -max_len=8192 \
      -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" "${extra[@]}" \
      2>build-fuzz/fuzz_"$t".log; then
    tail -40 build-fuzz/fuzz_"$t".log >&2
    echo "fuzz_$t found a problem; the input is in $findings/ (replay: build-fuzz/fuzz_$t FILE)" >&2
    return 1
  fi
  echo "== fuzz_$t: $(grep -E "stat::number_of_executed_units|stat::peak_rss_mb" build-fuzz/fuzz_"$t".log | tr -s ' \n' ' ')"
}

# A libFuzzer run uses one core: as many targets run at once as there are
# cores, each for the whole $seconds.
failed=0 running=0
for t in "${targets[@]}"; do
  if ((running >= $(nproc))); then
    wait -n || failed=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n || failed=1
  running=$((running - 1))
done
exit "$failed"
