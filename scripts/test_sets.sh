# Sourced by CI's scripts: the tests that the runs after the plain suite on
# Debian 12 (which runs every test) leave out, each set with why. Names are
# CTest's, exact.
#
# DEVICE_ONLY_TESTS: GPU tests that differ from the kept GPU tests only in
# what the device runs (the path integrator's megakernel, Whitted's, rays a
# lane, the SPD scenes' shapes, the watertight triangle test). Their host
# code is what the kept tests run (the megakernel's dispatch among them:
# GpuWavefront.RendersWhatTheMegakernelRenders, the ray log, the shadow
# queue); their time is lavapipe's compile and trace. The address run and
# Debian 13 leave them out.
DEVICE_ONLY_TESTS=(
  GpuPathIntegrator.UnderTheMegakernel
  GpuWavefront.TheImageIsTheSameWhateverTheRaysALane
  GpuWavefront.WhittedRendersWhatTheMegakernelRenders
  GpuPath.NoRayPassesBetweenTheTrianglesOfAClosedMesh
)
for scene in teapot_s6 balls_s4 gears_s4 tree_s11 rings_s3 mount_s3; do
  DEVICE_ONLY_TESTS+=("Spd/GpuSpdScenes.MatchTheCpuPathThroughEveryArray/\"$scene\"")
done
# ADDRESS_SKIPPED_TESTS: also left out of the address run. CliScenes renders
# the same code 174 times (29 scenes, 3 grids, 2 modes), 305 s under the
# sanitizer against 58 s plain on 2 cores; the sanitized suite's other
# tests render every grid and mode, and the SPD scenes.
ADDRESS_SKIPPED_TESTS=("${DEVICE_ONLY_TESTS[@]}" CliScenes.EveryShippedSceneRendersInEveryGridAndMode)
# DEBIAN13_SKIPPED_TESTS: also left out in the Debian 13 root: the
# measuring knobs that are no device's default (the shadow queue, 8-wide
# nodes: docs/design/gpu.md), and the light-field page, whose code is the
# page's own JavaScript, run in the same playwright-core.
DEBIAN13_SKIPPED_TESTS=("${DEVICE_ONLY_TESTS[@]}" GpuPath.TheShadowQueueRendersWhatTheKernelTracesItself
  GpuPath.EightWideNodesMatchTheCpuPath Web.page)

# test_regex NAME...: an anchored CTest regular expression matching exactly
# the names given.
test_regex() {
  local out="" name
  for name in "$@"; do
    name=$(printf '%s' "$name" | sed 's/[][\.*^$()+?{}|]/\\&/g')
    out+="${out:+|}$name"
  done
  printf '^(%s)$' "$out"
}

# ctest_ignore_file NAME...: a CTestCustom.cmake that makes CTest skip the
# names given (CTEST_CUSTOM_TESTS_IGNORE), for a build folder not made yet.
ctest_ignore_file() {
  local name
  printf 'list(APPEND CTEST_CUSTOM_TESTS_IGNORE'
  for name in "$@"; do printf ' "%s"' "${name//\"/\\\"}"; done
  printf ')\n'
}

# require_tests BUILD NAME...: fails, naming it, when a name given is not a
# test of build folder BUILD, so that a renamed test is not silently run
# again where a list above meant to leave it out.
require_tests() {
  local dir=$1 name listed
  shift
  listed=$(ctest --test-dir "$dir" -N | sed -n 's/^ *Test *#[0-9]*: //p')
  for name in "$@"; do
    grep -qxF -- "$name" <<< "$listed" || { echo "scripts/test_sets.sh: no test '$name' in $dir" >&2; return 1; }
  done
}
