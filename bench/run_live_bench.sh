#!/usr/bin/env bash
# holoray live's frames per second (issue 56): a 3840x2160 panel image
# (examples/displays/lenticular_4k.toml: a slanted lenticular sheet over RGB
# subpixels) and a Looking Glass Portrait's 1536x2048 native image
# (examples/displays/looking_glass_example_calibration.json) of the SPD's
# balls_s4 and gears_s4, each a shot playing (the scene turning 15 degrees
# over 48 frames at 24 fps: laid out on the device again every frame, as a
# moving shot is), shown under Xvfb on DEVICE. Per case: frames per second
# over FRAMES frames after the first (holoray live's own count: the scene
# moved and laid out, traced, packed and presented; no file written), and,
# in the same run, the baselines: `holoray animate --device DEVICE` of
# FRAMES + 1 frames of the same shot, seconds a frame (the scene built and
# uploaded once, each frame traced, read back and written: what a user did
# before live), and live showing an empty shot (the do-nothing baseline:
# rays that meet nothing, the pack and the present). Each live run's frame
# split too, as live prints it: the moved scene laid out and uploaded, the
# trace, the pack and show (ms, means).
# QUICK=1: both panels a quarter as wide and tall (960x540, 384x512, the same
# lenses), for a CPU device (lavapipe) where the full sizes take minutes a frame.
# OFFSCREEN=1: live runs with --offscreen instead of in a window under Xvfb
# (each frame packed and copied on the device to an image of the window's
# size as a shown one is, not presented, no vsync): for the GPU machines,
# which have no display and whose driver presents to no Xvfb.
# Prints a markdown table.
# Usage: bash bench/run_live_bench.sh  (DEVICE=gpu FRAMES=60 QUICK=1 OFFSCREEN=1 HOLORAY_SHARED=../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
shared=$(cd "${HOLORAY_SHARED:-../shared}" && pwd)
device=${DEVICE:-gpu}
frames=${FRAMES:-60}
[[ -d $shared/scenes/nff ]] || { echo "run_live_bench.sh: needs $shared/scenes" >&2; exit 1; }
[[ -x build/holoray ]] || { echo "run_live_bench.sh: build build/holoray first" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
panel=examples/displays/lenticular_4k.toml
portrait=examples/displays/looking_glass_example_calibration.json
if [[ -n ${QUICK:-} ]]; then
  sed 's/^resolution = \[3840, 2160\]/resolution = [960, 540]/' "$panel" > "$tmp/panel.toml"
  sed -e 's/"screenW": {"value": 1536.0}/"screenW": {"value": 384.0}/' -e 's/"screenH": {"value": 2048.0}/"screenH": {"value": 512.0}/' \
    -e 's/"DPI": {"value": 324.0}/"DPI": {"value": 81.0}/' "$portrait" > "$tmp/portrait.json"
  panel=$tmp/panel.toml portrait=$tmp/portrait.json
fi
declare -A cameras=([panel]="--display $panel" [portrait]="--looking-glass $portrait")
printf 'v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\nl 5 5 5\nb 0.1 0.1 0.1\n' > "$tmp/empty.nff"
# A shot of one scene file turning about its vertical axis.
shot() {
  printf 'frames = 48\nfps = 24\n[array]\nlenses = [64, 64]\npixels_per_lens = 8\n[[object]]\nscene = "%s"\n' "$1"
  printf '[[object.key]]\nframe = 0\nrotate = [0, 0, 0]\n[[object.key]]\nframe = 47\nrotate = [0, 0, 15]\n'
}
# holoray live's "frames N shown in S s (F fps)": F, frames after the first per second.
live_fps() {
  if [[ -n ${OFFSCREEN:-} ]]; then
    build/holoray live --shot "$1" $2 --play --device "$device" --offscreen \
      --exit-after $((frames + 1)) > "$tmp/live.log" 2>&1 || { cat "$tmp/live.log" >&2; exit 1; }
  else
    xvfb-run -a -s "-screen 0 1280x1024x24" build/holoray live --shot "$1" $2 --play --device "$device" --windowed \
      --exit-after $((frames + 1)) > "$tmp/live.log" 2>&1 || { cat "$tmp/live.log" >&2; exit 1; }
  fi
  sed -n 's/.*(\([0-9.]*\) fps).*/\1/p' "$tmp/live.log"
}
# The last live run's mean split of a frame, "layout / trace / show" in ms.
live_split() {
  sed -n 's/^a frame    layout \([0-9.]*\) ms, trace \([0-9.]*\) ms, show \([0-9.]*\) ms.*/\1 \/ \2 \/ \3/p' "$tmp/live.log"
}
animate_s() {
  local start end
  rm -rf "$tmp/frames"
  start=$(date +%s.%N)
  build/holoray animate "$1" $2 --device "$device" --frames 0:$frames -q -o "$tmp/frames"
  end=$(date +%s.%N)
  awk "BEGIN { printf \"%.4f\", ($end - $start) / ($frames + 1) }"
}
echo "Command: DEVICE=$device FRAMES=$frames${QUICK:+ QUICK=1}${OFFSCREEN:+ OFFSCREEN=1} bash bench/run_live_bench.sh"
echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo "Device: $(build/holoray devices | head -n 1)"
echo
echo "| image | scene | live, frames/s | live, ms a frame | live, layout / trace / show ms | animate --device $device, ms a frame | animate / live | live, empty shot, frames/s | empty shot, layout / trace / show ms |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|"
shot "$tmp/empty.nff" > "$tmp/empty.toml"
for camera in panel portrait; do
  empty=$(live_fps "$tmp/empty.toml" "${cameras[$camera]}")
  empty_split=$(live_split)
  for scene in balls_s4 gears_s4; do
    shot "$shared/scenes/nff/$scene.nff" > "$tmp/$scene.toml"
    fps=$(live_fps "$tmp/$scene.toml" "${cameras[$camera]}")
    split=$(live_split)
    animate=$(animate_s "$tmp/$scene.toml" "${cameras[$camera]}")
    awk -v c="$camera" -v s="$scene" -v f="$fps" -v a="$animate" -v e="$empty" -v sp="$split" -v es="$empty_split" \
      'BEGIN { printf "| %s | %s | %.3g | %.0f | %s | %.0f | %.2f | %.3g | %s |\n", c, s, f, 1000 / f, sp, 1000 * a, a * f, e, es }'
  done
done
