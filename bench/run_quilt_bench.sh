#!/usr/bin/env bash
# Looking Glass quilts (issue 14): an 8x6 quilt of 420x560-pixel views
# (Looking Glass Portrait's 3360x3360) rendered in one call (`render --quilt
# 8x6`) against the same 48 views rendered one by one (`render --quilt 8x6
# --quilt-view K`, 48 processes, as a script driving any renderer view by
# view would), alternated for ROUNDS rounds in one run; medians of the whole
# wall time. The one-by-one tiles are checked equal to the quilt's. Scenes:
# examples/primitives.nff, and the SPD teapot when ../shared is there.
# Writes bench/quilt_results.md.
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
scenes=(examples/primitives.nff)
[ -f ../shared/scenes/nff/teapot_s6.nff ] && scenes+=(../shared/scenes/nff/teapot_s6.nff)
nothing=$(nothing_median)
{
  echo "# Quilts in one call against view by view (\`bash bench/run_quilt_bench.sh\`)"
  echo
  echo "Machine: $(machine); $(date -u +%Y-%m-%d); $ROUNDS rounds alternated, medians of the wall time."
  echo "Do-nothing baseline (\`holoray --help\`, whole process): $nothing s."
  echo
  echo "| scene | quilt 8x6 of 420x560, one call s | the 48 views one by one s | one call / one by one |"
  echo "|---|---:|---:|---:|"
} > bench/quilt_results.md
for scene in "${scenes[@]}"; do
  n=$(basename "$scene" .nff)
  for r in $(seq "$ROUNDS"); do
    t0=$(now)
    "$bin" render "$scene" --quilt 8x6 -o "$tmp/q.png" -q
    t1=$(now)
    for k in $(seq 0 47); do "$bin" render "$scene" --quilt 8x6 --quilt-view "$k" -o "$tmp/v$k.png" -q; done
    t2=$(now)
    elapsed "$t0" "$t1" >> "$tmp/$n.quilt"
    elapsed "$t1" "$t2" >> "$tmp/$n.views"
  done
  # The views tiled as the quilt lays them out (view 0 bottom left) equal the quilt.
  for k in $(seq 0 47); do
    x=$(( (k % 8) * 420 )); y=$(( (5 - k / 8) * 560 ))
    oiiotool "$tmp/q_qs8x6a0.75.png" --cut "420x560+$x+$y" -o "$tmp/tile.png"
    if ! "$bin" compare "$tmp/v$k.png" "$tmp/tile.png" | grep -q '^all .* inf$'; then echo "view $k differs from its tile" >&2; exit 1; fi
  done
  q=$(median < "$tmp/$n.quilt"); v=$(median < "$tmp/$n.views")
  echo "| $n | $(printf %.3f "$q") | $(printf %.3f "$v") | $(awk -v a="$q" -v b="$v" 'BEGIN {printf "%.2fx", a / b}') |" >> bench/quilt_results.md
  echo "$n done"
done
cat bench/quilt_results.md
