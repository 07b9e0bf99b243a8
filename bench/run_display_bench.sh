#!/usr/bin/env bash
# Native panel images (issue 14): a 3840x2160 slanted-lenticular panel
# (examples/displays/lenticular_4k.toml, RGB subpixels: three lines per
# pixel) against today's 3840x2160 EIA (lenticular, 960 lenses x 4 px, one
# line per pixel) and the same panel traced one line per pixel (subpixels =
# "none"), alternated for ROUNDS rounds in one run. Medians of the trace
# time and of the whole process; the do-nothing baseline is `holoray
# --help`. Scenes: examples/primitives.nff, and the SPD teapot when
# ../shared is beside the checkout. Writes bench/display_results.md.
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
sed 's/^subpixels = "rgb".*/subpixels = "none"/' examples/displays/lenticular_4k.toml > "$tmp/whole.toml"
scenes=(examples/primitives.nff)
[ -f ../shared/scenes/nff/teapot_s6.nff ] && scenes+=(../shared/scenes/nff/teapot_s6.nff)
declare -A args=(
  [eia]="--grid lenticular --lenses 960x1 --pixels-per-lens 4 --rows 2160"
  [whole]="--display $tmp/whole.toml"
  [panel]="--display examples/displays/lenticular_4k.toml"
)
nothing=$(nothing_median)
{
  echo "# Native panel images against today's EIA (\`bash bench/run_display_bench.sh\`)"
  echo
  echo "Machine: $(machine); $(date -u +%Y-%m-%d); $ROUNDS rounds alternated, medians."
  echo "Do-nothing baseline (\`holoray --help\`, whole process): $nothing s."
  echo
  echo "| scene | image (3840x2160) | lines | trace s | whole process s | trace / EIA |"
  echo "|---|---|---:|---:|---:|---:|"
} > bench/display_results.md
for scene in "${scenes[@]}"; do
  n=$(basename "$scene" .nff)
  for r in $(seq "$ROUNDS"); do
    for k in eia whole panel; do
      t0=$(now)
      # shellcheck disable=SC2086
      "$bin" render "$scene" ${args[$k]} -o "$tmp/$k.png" > "$tmp/$k.log"
      t1=$(now)
      awk '/^trace/ {print $2}' "$tmp/$k.log" >> "$tmp/$n.$k.trace"
      elapsed "$t0" "$t1" >> "$tmp/$n.$k.wall"
    done
  done
  eia=$(median < "$tmp/$n.eia.trace")
  for k in eia whole panel; do
    case $k in
      eia) label="EIA, 960 lenticules x 4 px (\`${args[eia]}\`)"; lines=8294400 ;;
      whole) label="panel, one line per pixel (subpixels = \"none\")"; lines=8294400 ;;
      panel) label="panel, RGB subpixels (\`--display examples/displays/lenticular_4k.toml\`)"; lines=24883200 ;;
    esac
    t=$(median < "$tmp/$n.$k.trace"); w=$(median < "$tmp/$n.$k.wall")
    echo "| $n | $label | $lines | $t | $(printf %.3f "$w") | $(awk -v a="$t" -v b="$eia" 'BEGIN {printf "%.2fx", a / b}') |" >> bench/display_results.md
  done
  echo "$n done"
done
cat bench/display_results.md
