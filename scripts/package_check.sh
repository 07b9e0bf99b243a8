#!/usr/bin/env bash
# CI: the Debian package works once installed. Builds build/ and its .deb
# (CPack), installs it with apt, then from an empty folder, with only the
# system's folders on PATH, checks that /usr/bin/holoray runs (--version, a
# small render of an installed example, an animation with --video, which loads
# the FFmpeg module from /usr/lib/holoray, a frame of holoray live under Xvfb,
# which loads the window module from there, a light-field page served by the
# HTTP module from there), that the man page and the bash
# completion are installed (the completion completing in bash), that Debian's
# python3 imports the module and renders with it, that examples/api builds
# against the installed C++ package (find_package(holoray)), and removes
# the package again (purged: nothing of it left), also when a check fails.
# Usage: bash scripts/package_check.sh
set -euo pipefail
cd "$(dirname "$0")/.."

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if dpkg-query -W -f='${Status}' holoray 2>/dev/null | grep -q "install ok installed"; then
  echo "package_check: the holoray package is installed already: remove it first (apt-get remove holoray)" >&2
  exit 1
fi

rm -f build/holoray_*.deb
cmake --build build --target package
debs=(build/holoray_*_amd64.deb)
((${#debs[@]} == 1)) || { echo "package_check: expected one build/holoray_*_amd64.deb, found ${debs[*]}" >&2; exit 1; }

tmp=$(mktemp -d)
cleanup() {
  cd /
  rm -rf "$tmp"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get purge -y -qq holoray >/dev/null || true
}
trap cleanup EXIT
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "./${debs[0]}"

cd "$tmp"
export PATH=/usr/sbin:/usr/bin:/sbin:/bin
[ "$(command -v holoray)" = /usr/bin/holoray ] || { echo "package_check: holoray is not /usr/bin/holoray" >&2; exit 1; }
holoray --version
holoray --version | head -1 | grep -Eq '^holoray [0-9]+\.[0-9]+\.[0-9]+ \(git ' || { echo "package_check: bad --version" >&2; exit 1; }
examples=/usr/share/holoray/examples
holoray render "$examples/primitives.nff" --lenses 16x16 --pixels-per-lens 4 -o t.png -q
[ -s t.png ] || { echo "package_check: render wrote no t.png" >&2; exit 1; }
holoray animate "$examples/shots/swinging_box.toml" -o frames --video s.mkv -q
[ -s s.mkv ] || { echo "package_check: animate --video wrote no s.mkv" >&2; exit 1; }
# holoray live from the package: the window module from /usr/lib/holoray, a
# frame shown under Xvfb on the GPU path's device (lavapipe here).
[ -f /usr/lib/holoray/holoray_glfw.so ] || { echo "package_check: no /usr/lib/holoray/holoray_glfw.so" >&2; exit 1; }
xvfb-run -a holoray live "$examples/primitives.nff" --lenses 16x16 --pixels-per-lens 4 --exit-after 1 --screenshot l.png -q
[ -s l.png ] || { echo "package_check: holoray live wrote no l.png" >&2; exit 1; }
# holoray web from the package: the page embedded in the library, served by
# the HTTP module from /usr/lib/holoray.
[ -f /usr/lib/holoray/holoray_http.so ] || { echo "package_check: no /usr/lib/holoray/holoray_http.so" >&2; exit 1; }
holoray web t.png --pixels-per-lens 4 -o page -q
holoray web --serve page --port 0 > serve.log &
for _ in $(seq 50); do grep -q http serve.log && break; sleep 0.1; done
url=$(sed -n 's/.* at \(http[^ ]*\) .*/\1/p' serve.log)
served=$(python3 -c "import sys, urllib.request; print(urllib.request.urlopen(sys.argv[1] + 'light_field.json').read().decode())" "$url")
kill %1
wait %1 2>/dev/null || true
grep -q '"format": "holoray-web 1"' <<<"$served" || { echo "package_check: holoray web --serve did not serve the page ($url)" >&2; exit 1; }
# Under mpirun, the installed holoray becomes /usr/lib/holoray/holoray-mpi:
# two ranks write the still of one process.
if [ -x /usr/lib/holoray/holoray-mpi ] && command -v mpirun >/dev/null; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe --bind-to none -np 2 \
    holoray render "$examples/primitives.nff" --lenses 16x16 --pixels-per-lens 4 -o m.png -q
  cmp t.png m.png || { echo "package_check: mpirun -np 2 holoray render wrote another image" >&2; exit 1; }
fi
if command -v man >/dev/null; then
  man -w holoray
else
  ls /usr/share/man/man1/holoray.1*
fi
completion=/usr/share/bash-completion/completions/holoray
[ -f "$completion" ] || { echo "package_check: no $completion" >&2; exit 1; }
got=$(bash -c ". $completion; COMP_WORDS=(holoray render --pix); COMP_CWORD=2; _holoray; echo \"\${COMPREPLY[*]}\"")
[ "$got" = --pixels-per-lens ] || { echo "package_check: completion of 'holoray render --pix' gave '$got'" >&2; exit 1; }
# The Python module, from Debian's python3 and nothing else on its path.
/usr/bin/python3 -c "
import holoray
scene = holoray.load_scene('$examples/primitives.nff')
eia = holoray.render(scene, holoray.LensArray(lenses=(8, 8), pixels_per_lens=4)).colour
assert eia.shape == (32, 32, 3) and eia.max() > 0, eia.shape
print('package_check: python3 renders', eia.shape, 'with holoray', holoray.__version__, 'from', holoray.__file__)
"
# The C++ API: the installed example project against the installed package.
cmake -S "$examples/api" -B api-build -G Ninja >/dev/null
cmake --build api-build
./api-build/sweep_pitch "$examples/primitives.nff" .
[ -s eia_8.png ] || { echo "package_check: the API example wrote no eia_8.png" >&2; exit 1; }
echo "package_check: ${debs[0]} installs, runs from /usr and has its man page and completion"
