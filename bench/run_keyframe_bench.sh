#!/usr/bin/env bash
# Where keyframes go (issue 12): `--keyframe-interval auto` against a fixed
# interval, reverse reprojection with colour reuse, full tracing timed in the
# same run (--report). Shots: bench/keyframe_shots/tree_hold_cut.toml (holds
# and a cut) with K = 8 and auto at 4 px; then the five bench shots (steady
# motion) with K = 8 and auto at the motion that places as many keyframes.
# Writes bench/keyframe_results.md. Needs ../shared beside the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/holoray
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{
  echo "# Keyframe placement: fixed interval against auto (\`bash bench/run_keyframe_bench.sh\`)"
  echo
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); reverse reprojection, colour reuse; 120 frames, 512x512; full tracing timed in the same run."
  echo
  echo "| shot | keyframes by | keyframes | full s | accelerated s | saved % | mean PSNR dB | min PSNR dB | hold mean PSNR dB | hold min PSNR dB | frames below hold |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
} > bench/keyframe_results.md
run() {  # shot-file label args...
  local shot=$1 label=$2
  shift 2
  "$bin" animate "$shot" -o "$tmp/out" --method reverse --reuse color "$@" --report "$tmp/r.md" -q
  row=$(sed -n '/^| frames/{n;n;p;q}' "$tmp/r.md")
  IFS='|' read -r _ frames keys full acc saved_s saved mean minp hmean hmin below _ <<<"$row"
  echo "| $(basename "$shot" .toml) | $label |$keys|$full|$acc|$saved|$mean|$minp|$hmean|$hmin|$below|" >> bench/keyframe_results.md
  echo "$(basename "$shot" .toml) $label: $keys keyframes, $saved% saved, mean PSNR $mean dB"
}
hc=bench/keyframe_shots/tree_hold_cut.toml
run "$hc" "K = 8" --keyframe-interval 8
run "$hc" "auto, 4 px" --keyframe-interval auto --keyframe-motion 4
# Steady motion: auto at the motion giving about the 16 keyframes of K = 8.
for pair in "balls 10" "gears 3.5" "moving 12" "teapot 20" "tree 1.5"; do
  read -r name px <<<"$pair"
  run "bench/shots/$name.toml" "K = 8" --keyframe-interval 8
  run "bench/shots/$name.toml" "auto, $px px" --keyframe-interval auto --keyframe-motion "$px"
done
