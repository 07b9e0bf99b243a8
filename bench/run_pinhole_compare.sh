#!/usr/bin/env bash
# The pinhole view against POV-Ray (issue 13): each SPD scene rendered by
# `holoray render --camera pinhole` and by POV-Ray 3.7 from the conversion of
# bench/nff_to_pov.py, both 512x512, no anti-aliasing, ray depth 5, sRGB
# PNGs; PSNR of holoray's image against POV-Ray's. Writes
# bench/pinhole_results.md. Needs ../shared/scenes, povray and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build}/holoray
shared=${HOLORAY_SHARED:-../shared}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=${SCENES:-"balls_s2 gears_s2 mount_s3 rings_s2 teapot_s6 tetra_s3 tree_s11"}
{
  echo "# Pinhole view against POV-Ray (\`bash bench/run_pinhole_compare.sh\`)"
  echo
  echo "512x512, no anti-aliasing, ray depth 5, sRGB PNGs. holoray: \`holoray render SCENE --camera pinhole --resolution 512x512 --encoding srgb\`; POV-Ray 3.7: \`povray +W512 +H512 -A\` on \`python3 bench/nff_to_pov.py SCENE\`."
  echo
  echo "| scene | PSNR dB | MSE |"
  echo "|---|---:|---:|"
  for s in $scenes; do
    nff=$shared/scenes/nff/$s.nff
    "$bin" render "$nff" --camera pinhole --resolution 512x512 --encoding srgb -o "$work/h.png" -q
    python3 bench/nff_to_pov.py "$nff" > "$work/s.pov" 2>/dev/null
    povray +I"$work/s.pov" +O"$work/p.png" +W512 +H512 -D -V +FN -A >/dev/null 2>&1
    read -r _ mse _ psnr < <("$bin" compare "$work/h.png" "$work/p.png" | grep '^all')
    echo "| $s | $psnr | $mse |"
  done
} > bench/pinhole_results.md
cat bench/pinhole_results.md
