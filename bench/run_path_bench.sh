#!/usr/bin/env bash
# The path integrator's speed against Cycles (issue 70): paths per second on
# the same scene, resolution, samples and bounces, on this machine's cores.
# The scenes are tests/blender/path_oracle.py's (hdri: Blender's courtyard
# world; room: a closed room lit by one area light), WIDTHxHEIGHT pixels,
# SAMPLES samples per pixel, 4 bounces (holoray --max-depth 5). Cycles: the
# oracle's render call (bpy.ops.render.render: its scene sync, BVH build
# and render), CPU, no denoiser, no adaptive sampling; holoray: its trace
# time and its whole process (`holoray render`, the scene read and built).
# ROUNDS rounds, the two alternating; medians. The do-nothing baseline:
# `holoray --help`. Writes bench/path_results.md.
# Usage: bash bench/run_path_bench.sh   (ROUNDS=3 SAMPLES=64 WIDTH=320 HEIGHT=240)
set -euo pipefail
cd "$(dirname "$0")/.."
SAMPLES=${SAMPLES:-64}
WIDTH=${WIDTH:-320}
HEIGHT=${HEIGHT:-240}
source bench/lib.sh
command -v blender >/dev/null || { echo "run_path_bench.sh: blender is not installed" >&2; exit 1; }
out=bench/path_results.md
{
  echo "# The path integrator against Cycles"
  echo
  echo "Measured by \`bash bench/run_path_bench.sh\` (ROUNDS=$ROUNDS, ${WIDTH}x${HEIGHT} px, $SAMPLES samples, 4 bounces) on"
  echo "$(machine), $(blender --version 2>/dev/null | head -1). Seconds are medians; paths are pixels x samples."
  echo
  echo "| scene | Cycles render | holoray trace | holoray process | paths/s Cycles | paths/s holoray (trace) | holoray / Cycles |"
  echo "|---|---:|---:|---:|---:|---:|---:|"
} > "$tmp/table"
for scene in hdri room; do
  : > "$tmp/cycles"; : > "$tmp/trace"; : > "$tmp/wall"
  for r in $(seq "$ROUNDS"); do
    blender -b --factory-startup --python tests/blender/path_oracle.py -- "$tmp/$scene" "$scene" "$SAMPLES" "$WIDTH" "$HEIGHT" \
      > /dev/null 2>&1
    python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds'])" "$tmp/$scene/oracle.json" >> "$tmp/cycles"
    world=(--environment-colour 0,0,0)
    [[ $scene == hdri ]] && world=(--environment /usr/share/blender/datafiles/studiolights/world/courtyard.exr)
    t0=$(now)
    "$bin" render "$tmp/$scene/scene.gltf" --camera pinhole --resolution "${WIDTH}x${HEIGHT}" --integrator path \
      --spp "$SAMPLES" --max-depth 5 --blender-principled --lights "$tmp/$scene/lights.toml" "${world[@]}" \
      -o "$tmp/$scene/holoray.exr" > "$tmp/summary"
    t1=$(now)
    elapsed "$t0" "$t1" >> "$tmp/wall"
    awk '/^trace/ {print $2}' "$tmp/summary" >> "$tmp/trace"
  done
  c=$(median < "$tmp/cycles"); t=$(median < "$tmp/trace"); w=$(median < "$tmp/wall")
  paths=$((WIDTH * HEIGHT * SAMPLES))
  awk -v s="$scene" -v c="$c" -v t="$t" -v w="$w" -v p="$paths" \
    'BEGIN {printf "| %s | %.2f s | %.2f s | %.2f s | %.2f M | %.2f M | %.2fx |\n", s, c, t, w, p / c / 1e6, p / t / 1e6, c / t}' \
    >> "$tmp/table"
done
{
  cat "$tmp/table"
  echo
  echo "Do-nothing baseline (\`holoray --help\`, the whole process): $(nothing_median) s."
} > "$out"
cat "$out"
