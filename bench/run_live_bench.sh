#!/usr/bin/env bash
# holoray live's frames per second (issue 56): a 3840x2160 panel image
# (examples/displays/lenticular_4k.toml, slanted lenticular over RGB
# subpixels) and a Looking Glass Portrait's 1536x2048 native image
# (examples/displays/looking_glass_example_calibration.json) of the SPD's
# balls_s4 and gears_s4, the view orbiting a little every frame (an --events
# replay: each frame placed and traced anew, as a playing shot would be),
# shown under Xvfb on DEVICE. Per case: frames per second over FRAMES frames
# after the first (holoray live's own count: tracing, packing and
# presenting, the title, no file written), and in the same run the
# baselines: `holoray render --device DEVICE` of the same still (a new
# process, the scene built and uploaded, the image read back and written:
# what a user did before live), and live on an empty scene (the
# do-nothing baseline: rays that meet nothing, the pack and the present).
# Prints a markdown table.
# Usage: bash bench/run_live_bench.sh  (DEVICE=gpu FRAMES=30 HOLORAY_SHARED=../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
shared=${HOLORAY_SHARED:-../shared}
device=${DEVICE:-gpu}
frames=${FRAMES:-30}
[[ -d $shared/scenes/nff ]] || { echo "run_live_bench.sh: needs $shared/scenes" >&2; exit 1; }
[[ -x build/holoray ]] || { echo "run_live_bench.sh: build build/holoray first" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf 'v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\nl 5 5 5\nb 0.1 0.1 0.1\n' > "$tmp/empty.nff"
for ((k = 1; k <= frames; ++k)); do echo "$k orbit 2 0"; done > "$tmp/orbit.txt"
declare -A cameras=(
  [panel]="--display examples/displays/lenticular_4k.toml"
  [portrait]="--looking-glass examples/displays/looking_glass_example_calibration.json"
)
# holoray live's "frames N shown in S s (F fps)": F, frames after the first per second.
live_fps() {
  xvfb-run -a -s "-screen 0 1280x1024x24" build/holoray live "$1" $2 --device "$device" --windowed \
    --events "$tmp/orbit.txt" --exit-after $((frames + 1)) > "$tmp/live.log" 2>&1 || { cat "$tmp/live.log" >&2; exit 1; }
  sed -n 's/.*(\([0-9.]*\) fps).*/\1/p' "$tmp/live.log"
}
render_s() {
  local start end
  start=$(date +%s.%N)
  build/holoray render "$1" $2 --device "$device" -q -o "$tmp/still.png"
  end=$(date +%s.%N)
  awk "BEGIN { printf \"%.2f\", $end - $start }"
}
echo "Command: DEVICE=$device FRAMES=$frames bash bench/run_live_bench.sh"
echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo "Device: $(build/holoray devices | head -n 1)"
echo
echo "| image | scene | live, frames/s | render --device $device, s a still | live, empty scene, frames/s |"
echo "|---|---|---|---|---|"
for camera in panel portrait; do
  empty=$(live_fps "$tmp/empty.nff" "${cameras[$camera]}")
  for scene in balls_s4 gears_s4; do
    nff=$shared/scenes/nff/$scene.nff
    echo "| $camera | $scene | $(live_fps "$nff" "${cameras[$camera]}") | $(render_s "$nff" "${cameras[$camera]}") | $empty |"
  done
done
