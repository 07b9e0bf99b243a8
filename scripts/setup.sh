#!/usr/bin/env bash
# Installs every Debian package holoray needs, then configures and builds
# Release into build/. Safe to rerun. Usage: bash scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Tested on Debian 12 (bookworm) and Debian 13 (trixie); elsewhere the
# package names below may differ, and apt says which.
release=$( (. /etc/os-release 2>/dev/null && echo "${ID:-unknown} ${VERSION_ID:-}") || echo unknown)
case $release in
  "debian 12" | "debian 13") ;;
  *) echo "setup.sh: holoray is tested on Debian 12 and Debian 13; this is '$release': trying anyway" >&2 ;;
esac

packages=(
  build-essential cmake ninja-build pkg-config
  help2man                  # the build's man page (build/holoray.1), made from --help
  libembree-dev libtbb-dev libpng-dev libopenexr-dev libjpeg-dev libgif-dev libstb-dev  # images (PNG, EXR, JPEG, GIF; PPM, Targa, BMP)
  openimageio-tools         # the tests' independent image decoder and docs/make_images.sh
  libcli11-dev libfmt-dev libtomlplusplus-dev libgtest-dev libgmock-dev libbenchmark-dev
  libassimp-dev             # meshes: OBJ, PLY, STL, glTF, 3DS, COLLADA, AC3D
  assimp-testmodels         # glTF and OBJ sample models: docs/guide/scenes.md and the README pictures
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev  # animate --video: FFV1 and H.264
  nlohmann-json3-dev        # Looking Glass calibration files (JSON)
  libvulkan-dev glslc       # the GPU path (--device gpu): Vulkan-Hpp's headers and the loader, the shader compiler
  mesa-vulkan-drivers       # lavapipe, a Vulkan device on the CPU: the GPU path's tests run on it where there is no GPU
  python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module (build/python) and its pytest suite, against Debian's python3
  blender                   # the add-on's tests (tests/blender), headless: Debian's Blender, which embeds Debian's python3
  libglfw3-dev              # holoray live: its window, monitors and input (the module holoray_glfw.so)
  xvfb xauth                # a display for holoray live's tests (xvfb-run) and for the guide's screenshots
  libopenmpi-dev openmpi-bin  # mpirun -np N holoray animate|render (optional in CMake; installed so the README's commands build it)
  clang libclang-rt-dev     # fuzz/run.sh and scripts/sanitize.sh (the release's own clang and its runtime)
  hyperfine                 # bench/run_startup_deps.sh: start-up per library
  tachyon povray            # bench/run_bench.sh: the yardsticks of issue 4; povray and tachyon the pinhole tests' references
  tachyon-doc               # bench/run_tachyon_compare.sh: Tachyon's manual and example scenes
  libcpp-httplib-dev        # holoray web --serve: the light-field page served on this machine
  chromium                  # the light-field page's tests (tests/web): headless, WebGL2 on SwiftShader
)
# The page's tests drive Chromium from Node (playwright-core, pinned in
# tests/web/package-lock.json): Debian's nodejs and npm where the machine
# has no Node of its own.
command -v npm >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

if [ ! -d tests/web/node_modules/playwright-core ] || [ tests/web/package-lock.json -nt tests/web/node_modules/.package-lock.json ]; then
  npm ci --prefix tests/web --no-audit --no-fund --loglevel=error
fi

cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build
