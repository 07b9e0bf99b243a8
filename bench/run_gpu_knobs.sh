#!/usr/bin/env bash
# The GPU path's measuring knobs against its default kernel, in one run (issue
# 55): for each of the four SPD scenes, 3840x2160 EIAs (240x135 lenses x 16
# px), the default and each variant alternate ROUNDS times (FRAMES frames
# after WARMUP, bench/gpu_frames.cpp), so that every ratio compares medians
# taken minutes apart at most on the same device. Variants: the shadow queue
# (HOLORAY_GPU_SHADOW_QUEUE=1), 8-wide nodes (HOLORAY_GPU_BVH_WIDTH=8), and
# both (docs/design/gpu.md). Prints a markdown table: each variant's medians
# in ms per frame (one per round), and its speed against the default's
# (the default's median of rounds over the variant's; the lower middle
# of an even count, as bench/lib.sh takes it). Not a test: on
# lavapipe (no GPU) QUICK=1 runs it as a check at 30x17 lenses.
# Usage: bash bench/run_gpu_knobs.sh  (DEVICE=gpu FRAMES=20 WARMUP=3 ROUNDS=2
#        QUICK=1 FRAMES_BIN=build/bench/holoray_gpu_frames HOLORAY_SHARED=../shared)
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${ROUNDS:-2}
source bench/lib.sh  # median, machine, gpu_bench_settings
gpu_bench_settings run_gpu_knobs.sh
rounds=$ROUNDS
if [[ -n ${QUICK:-} ]]; then rounds=1; fi
variants=("HOLORAY_GPU_SHADOW_QUEUE=1" "HOLORAY_GPU_BVH_WIDTH=8" "HOLORAY_GPU_SHADOW_QUEUE=1 HOLORAY_GPU_BVH_WIDTH=8")
# One run's median ms per frame, with the variant's variables (none: the default).
median_ms() {
  local scene=$1; shift
  env "$@" "$frames_bin" "$shared/scenes/nff/$scene.nff" --device "$device" --lenses "$lenses" --ppl 16 \
    --frames "$frames" --warmup "$warmup" | sed -n 's/.* ms_median=\([^ ]*\).*/\1/p'
}
echo "Command: DEVICE=$device FRAMES=$frames WARMUP=$warmup ROUNDS=$rounds${QUICK:+ QUICK=1} bash bench/run_gpu_knobs.sh"
echo "Machine: $(machine); $(git rev-parse --short HEAD 2>/dev/null || echo unknown); lenses $lenses x 16 px"
echo
echo "| scene | default ms |$(printf ' %s ms | speed |' "${variants[@]}")"
echo "|---|---:|$(printf -- '---:|---:|%.0s' "${variants[@]}")"
for scene in balls_s4 gears_s4 teapot_s6 tree_s11; do
  base=() runs=()
  for ((r = 0; r < rounds; ++r)); do
    base+=("$(median_ms "$scene")")
    for k in "${!variants[@]}"; do
      # shellcheck disable=SC2086  # a variant is words: VAR=value ...
      runs[k]="${runs[k]:-} $(median_ms "$scene" ${variants[k]})"
    done
  done
  b=$(printf '%s\n' "${base[@]}" | median)
  row="| $scene | ${base[*]} |"
  for k in "${!variants[@]}"; do
    v=$(echo "${runs[k]}" | xargs -n1 | median)
    row+=" $(echo "${runs[k]}" | xargs) | $(awk -v b="$b" -v v="$v" 'BEGIN {printf "%.2fx", b / v}') |"
  done
  echo "$row"
done
