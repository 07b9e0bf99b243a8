#!/usr/bin/env bash
# Sanitizer runs (issue 5). `address`: the test suite built with
# AddressSanitizer + UndefinedBehaviorSanitizer (any report fails the test
# that made it), all but the tests scripts/test_sets.sh names. `thread`: ThreadSanitizer on the tests that run work on
# several threads (rendering, reprojection, determinism, interrupted runs).
# Each builds into its own folder (build-asan/, build-tsan/) with clang: the
# library at -O1, the CLI's front end and the tests at -O0 (they parse and
# compare; HOLORAY_FRONT_END_FLAGS), all with line tables only, which is what
# the sanitizers' stack traces read. The Python module is left out (an instrumented
# extension needs the sanitizer's runtime preloaded into python3); the API it
# calls is tested here through tests/test_api.cpp. Usage: bash scripts/sanitize.sh [address|thread]...
set -euo pipefail
cd "$(dirname "$0")/.."
kinds=("$@")
((${#kinds[@]})) || kinds=(address thread)
jobs=$(nproc)
# The tests that run work on several threads: rendering, reprojection (forward
# and reverse), filling,
# determinism over thread counts and tile orders (the shadow cache's too), and the
# interrupted sequences.
TSAN_TESTS="^(Api|Render|ShadowCache|PathologicalScenes|Reprojection|ReverseReprojection|PinholeView|Tachyon|Fill|Temporal|Sequence|AnimateDeterminism|AnimateCli|Signals/AnimateInterrupted|DisplayRender|Quilt|LookingGlass)"
# The bad-input cases that are usage errors (status 2: CLI11 and our option
# validators refuse the command line before any file is read or anything
# rendered) only parse options: the plain suite runs them, the address run
# leaves them out.
usage_only=$(awk '/^\[\[case\]\]/ {id = ""} /^id = / {gsub(/"/, "", $3); id = $3} /^status = 2$/ && id {print id}' \
  tests/data/bad_inputs.toml | paste -sd'|')
# The tests the address run leaves out, and why: scripts/test_sets.sh.
source scripts/test_sets.sh
for kind in "${kinds[@]}"; do
  case $kind in
    address)
      dir=build-asan
      flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
      std_threads=OFF
      filter=""
      # CTest's name of a value-parameterized case ends in "  # GetParam() = N".
      exclude="^Cases/BadInput\.ExitsWithItsStatusAndMessage/($usage_only)(  # GetParam\(\) = [0-9]+)?\$|$(test_regex "${ADDRESS_SKIPPED_TESTS[@]}")"
      gpu=ON
      export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
      # lavapipe keeps a one-time table (built under pthread_once when the
      # devices are listed) in its own globals, and the Vulkan loader unloads
      # it at vkDestroyInstance: LeakSanitizer, no longer seeing those globals,
      # reports the table as a 128-byte leak from an unknown module in every
      # process that used the device. Preloaded, the driver stays mapped and
      # its globals stay roots; a leak of ours is reported as before.
      # awk reads to the end: leaving early would end ldconfig on SIGPIPE,
      # which pipefail turns into this script's exit status (141).
      preload=$(ldconfig -p | awk '/libvulkan_lvp\.so / && !found {print $NF; found = 1}')
      export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ;;
    thread)
      dir=build-tsan
      flags="-fsanitize=thread"
      # oneTBB is not instrumented, so TSan cannot see its hand-off of work:
      # this build schedules our tiles on std::threads instead (HOLORAY_STD_THREADS),
      # and only Embree's internal BVH build, which runs on oneTBB, is
      # suppressed (scripts/tsan.supp).
      std_threads=ON
      filter="$TSAN_TESTS"
      exclude=""
      # None of those tests uses the GPU path: the build leaves it and its
      # shaders out (glslc alone is minutes of a 2-core machine).
      gpu=OFF
      preload=""
      export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp" ;;
    *) echo "scripts/sanitize.sh: unknown kind '$kind' (address or thread)" >&2; exit 2 ;;
  esac
  # The build type's own flags are replaced: RelWithDebInfo's -O2 -g would
  # come after ours and win.
  cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
    -DHOLORAY_FRONT_END_FLAGS=-O0 -DCMAKE_EXE_LINKER_FLAGS="$flags" -DHOLORAY_BENCH=OFF \
    -DHOLORAY_STD_THREADS=$std_threads -DHOLORAY_GPU=$gpu -DHOLORAY_MPI=OFF -DHOLORAY_PYTHON=OFF >/dev/null
  cmake --build "$dir"
  [ "$kind" != address ] || require_tests "$dir" "${ADDRESS_SKIPPED_TESTS[@]}"
  echo "== $kind sanitizer: tests${filter:+ matching $filter}"
  LD_PRELOAD=$preload ctest --test-dir "$dir" --output-on-failure -j"$jobs" ${filter:+-R "$filter"} ${exclude:+-E "$exclude"}
done
