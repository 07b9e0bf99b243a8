#!/usr/bin/env bash
# What each library costs a process at start-up: an empty main() linked
# against it alone, median of 20 runs (hyperfine), with the shared libraries
# the loader maps. The last rows are what holoray keeps out of every
# process: FFmpeg (a module loaded on the first video) and OpenImageIO (not
# used). Prints a markdown table.
# Usage: bash bench/run_startup_deps.sh
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
command -v hyperfine >/dev/null || { echo "run_startup_deps.sh: hyperfine is missing (bash scripts/setup.sh installs it)" >&2; exit 1; }
echo 'int main(void) { return 0; }' > "$tmp/empty.c"
echo "| linked against | what for | shared libraries mapped | start-up, ms (median of 20) |"
echo "|---|---|---:|---:|"
while IFS='|' read -r libs what; do
  # shellcheck disable=SC2086  # several -l flags in one row
  gcc -o "$tmp/e" "$tmp/empty.c" -Wl,--no-as-needed $libs
  n=$(ldd "$tmp/e" | wc -l)
  hyperfine -N -w 3 -r 20 --export-json "$tmp/h.json" "$tmp/e" > /dev/null 2>&1
  ms=$(python3 -c "import json,sys; print(f\"{json.load(open(sys.argv[1]))['results'][0]['median'] * 1000:.1f}\")" "$tmp/h.json")
  echo "| \`${libs:-(nothing)}\` | $what | $n | $ms |"
done <<'LIBS'
|the do-nothing baseline
-lfmt|messages
-ltbb|threads (oneTBB)
-lembree3|ray tracing (Embree 3)
-lpng16|PNG
-lOpenEXR-3_1|OpenEXR
-ljpeg|JPEG input
-lgif|animated GIF
-lstb|PPM, Targa, BMP input
-ltomlplusplus|shot and display files
-lassimp|meshes
-lmpi|mpirun (OpenMPI)
-lavformat -lavcodec -lswscale -lavutil|video (FFmpeg): a module loaded on the first video only
-lOpenImageIO|not linked; what one image library cost before
LIBS
