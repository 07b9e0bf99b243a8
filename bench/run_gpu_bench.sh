#!/usr/bin/env bash
# The GPU path's frames (issue 55): 3840x2160 EIAs (240x135 lenses x 16 px)
# of the four SPD scenes (teapot_s6, balls_s4, gears_s4, tree_s11), each
# rendered WARMUP + FRAMES times by one built Renderer on DEVICE
# (bench/gpu_frames.cpp, the public API). Per scene: the dispatches' time
# per frame (ray generation, traversal and shading: median, min, max of
# FRAMES after the warm-up; the scene's upload and the image's readback
# apart), frames per second, rays per second, BVH nodes visited and
# primitives tested per ray, and against the CPU path on the same machine in
# the same run: its trace seconds, the PSNR of the GPU's image (8-bit
# scale), the share of pixels whose depth differs by more than 1e-4
# relative where both hit, and the share whose object id is equal. The
# do-nothing baseline: the same EIA of an empty scene (the dispatches, the
# lines clipped against no box, the image written).
# Prints a markdown table. Not a timed test: on lavapipe (no GPU), QUICK=1
# runs it as a check at 30x17 lenses.
# Usage: bash bench/run_gpu_bench.sh  (DEVICE=gpu FRAMES=20 WARMUP=3 QUICK=1
#        FRAMES_BIN=build/bench/holoray_gpu_frames HOLORAY_SHARED=../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh  # gpu_bench_settings, machine, $tmp
gpu_bench_settings run_gpu_bench.sh
# An empty scene: a viewpoint and a light, nothing to meet.
printf 'v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 512 512\nl 5 5 5\nb 0.1 0.1 0.1\n' > "$tmp/empty.nff"
run() { "$frames_bin" "$1" --device "$device" --lenses "$lenses" --ppl 16 --frames "$frames" --warmup "$warmup" "${@:2}"; }
field() { sed -n "s/.* $1=\\([^ ]*\\).*/\\1/p"; }
echo "Command: DEVICE=$device FRAMES=$frames WARMUP=$warmup${QUICK:+ QUICK=1} bash bench/run_gpu_bench.sh"
echo "Machine: $(machine); $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
nothing=$(run "$tmp/empty.nff")
echo "Device: $(echo "$nothing" | sed -n 's/.*device="\([^"]*\)".*/\1/p'); image $(echo "$nothing" | field size)"
echo "Do-nothing baseline (an empty scene): $(echo "$nothing" | field ms_median) ms per frame"
echo
echo "| scene | ms/frame median (min-max) | fps | Mrays/s | nodes/ray | prims/ray | readback ms | upload+build s | CPU trace s (same machine) | PSNR dB vs CPU | depth off % | id equal % |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for scene in teapot_s6 balls_s4 gears_s4 tree_s11; do
  line=$(run "$shared/scenes/nff/$scene.nff" --cpu)
  f() { echo "$line" | field "$1"; }
  echo "| $scene | $(f ms_median) ($(f ms_min)-$(f ms_max)) | $(f fps) | $(f mrays_s) | $(f nodes_per_ray) | $(f prims_per_ray) | $(f readback_ms) | $(f setup_s) | $(f cpu_trace_s) | $(f psnr_db) | $(f depth_off_pct) | $(f id_equal_pct) |"
done
# Each integrator twice on the same EIAs: the megakernel
# (HOLORAY_GPU_WAVEFRONT=0), then the wavefront (=1) in the same run; speed
# is the megakernel's time over the wavefront's, and lanes' use the
# wavefront traversals' (nodes visited over their lanes' steps): what the
# measured rule that picks a frame's schedule (src/gpu/wavefront.cpp,
# wave_rule) is checked against.
schedule_header() {
  echo
  echo "$1: the megakernel (HOLORAY_GPU_WAVEFRONT=0), then the wavefront (=1) in the same run;"
  echo "speed is the megakernel's time over the wavefront's; lanes' use is the wavefront traversals'"
  echo "(nodes visited over their lanes' steps):"
  echo
  echo "| scene | rays/pixel | megakernel ms/frame median (min-max) | fps | wavefront ms/frame median (min-max) | fps | speed | lanes' use | Mrays/s | nodes/ray |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
}
schedule_row() {
  local name=$1 mega wave
  mega=$(HOLORAY_GPU_WAVEFRONT=0 run "${@:2}")
  wave=$(HOLORAY_GPU_WAVEFRONT=1 run "${@:2}")
  m() { echo "$mega" | field "$1"; }
  w() { echo "$wave" | field "$1"; }
  local pixels
  pixels=$(m size | awk -Fx '{ print $1 * $2 }')
  echo "| $name | $(awk -v r="$(m rays)" -v p="$pixels" 'BEGIN { printf "%.1f", r / p }')" \
       "| $(m ms_median) ($(m ms_min)-$(m ms_max)) | $(m fps) | $(w ms_median) ($(w ms_min)-$(w ms_max)) | $(w fps)" \
       "| $(awk -v a="$(m ms_median)" -v b="$(w ms_median)" 'BEGIN { printf "%.2fx", a / b }') | $(w lanes_use)" \
       "| $(m mrays_s) | $(m nodes_per_ray) |"
}
schedule_header "Whitted's integrator"
for scene in teapot_s6 balls_s4 gears_s4 tree_s11; do schedule_row "$scene" "$shared/scenes/nff/$scene.nff"; done
# The path integrator (issue 70) at SPP samples per pixel on the same EIAs:
# the four SPD scenes under their point lights, and two scenes lit as the
# path integrator lights them: the Cornell box's area light and a glTF under
# Blender's courtyard HDRI (ENVIRONMENT, where Blender's data is at hand).
spp=${SPP:-1}
environment=${ENVIRONMENT:-/usr/share/blender/datafiles/studiolights/world/courtyard.exr}
schedule_header "The path integrator, $spp sample(s) per pixel, 5 bounces at most"
path_row() { schedule_row "$1" "${@:2}" --integrator path --spp "$spp"; }
for scene in teapot_s6 balls_s4 gears_s4 tree_s11; do path_row "$scene" "$shared/scenes/nff/$scene.nff"; done
path_row "cornell_box (area light)" examples/lights/cornell_box.nff --lights examples/lights/cornell_box.toml
if [[ -f $environment ]]; then
  path_row "swinging_box ($(basename "$environment"))" examples/swinging_box.gltf --environment "$environment"
fi
