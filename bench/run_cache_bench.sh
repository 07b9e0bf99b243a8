#!/usr/bin/env bash
# Shadow cache on stills (issue 12): each scene's 2048x2048 EIA (128x128
# lenses x 16 px) rendered with --cache off and --cache on, alternated for
# ROUNDS rounds in one run; median trace time of each, and the PSNR of the
# cached image against the uncached one (float EXR, all channels). Writes
# bench/cache_results.md. Needs ../shared beside the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
{
  echo "# Shadow cache on stills (\`bash bench/run_cache_bench.sh\`)"
  echo
  echo "Machine: $(machine); 2048x2048 EIA, 128x128 lenses x 16 px, cells of one lens pitch; $ROUNDS rounds alternated, medians of the trace time."
  echo
  echo "| scene | off s | on s | speed-up | PSNR dB | queries by cells | traced | sample rays | cache MiB |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
} > bench/cache_results.md
for scene in balls_s4 gears_s4 teapot_s6 tree_s11; do
  f=../shared/scenes/nff/$scene.nff
  for r in $(seq "$ROUNDS"); do
    for c in off on; do
      "$bin" render "$f" --lenses 128x128 --pixels-per-lens 16 --cache $c -o "$tmp/$c.exr" > "$tmp/$c.log"
      awk '/^trace/ {print $2}' "$tmp/$c.log" >> "$tmp/$scene.$c"
    done
  done
  off=$(median < "$tmp/$scene.off"); on=$(median < "$tmp/$scene.on")
  psnr=$("$bin" compare "$tmp/off.exr" "$tmp/on.exr" | awk '/^all/ {print $4}')
  line=$(grep '^cache' "$tmp/on.log")
  shares=$(sed -E 's/.*: ([0-9.]+)% by cells, ([0-9.]+)% traced; ([0-9]+) sample rays.*/\1% | \2% | \3/' <<<"$line")
  mib=$(sed -E 's/.* ([0-9.]+) MiB .*/\1/' <<<"$line")
  echo "| $scene | $off | $on | $(awk -v a="$off" -v b="$on" 'BEGIN {printf "%.2fx", a / b}') | $psnr | $shares | $mib |" >> bench/cache_results.md
  echo "$scene: off $off s, on $on s, PSNR $psnr dB"
done
