#!/usr/bin/env bash
# Temporal reprojection benchmark (issue 3): every shot in bench/shots, once
# per method, each with --report (which also ray traces every frame in full,
# so the full and accelerated times come from the same run). Writes
# bench/animation_results.md (the Table 2 comparison) and the per-run reports
# in bench/animation_reports/. Needs ../shared beside the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/holoray
out=bench/animation_reports
mkdir -p "$out"
K=${K:-8}
methods=("color interpolate" "color trace" "geometry trace")
{
  echo "# Temporal reprojection: time saved and quality (\`bash bench/run_animation_bench.sh\`)"
  echo
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); keyframe interval $K; full-ray-tracing time measured in the same run (--report)."
  echo
  echo "| shot | reuse | fill | frames | full s | accelerated s | saved % | mean PSNR dB | min PSNR dB | exact frames | reprojected % | traced % |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
} > bench/animation_results.md
for shot in bench/shots/*.toml; do
  name=$(basename "$shot" .toml)
  for m in "${methods[@]}"; do
    read -r reuse fill <<<"$m"
    report="$out/${name}_${reuse}_${fill}.md"
    "$bin" animate "$shot" -o "/tmp/holoray_bench_$name" --keyframe-interval "$K" --reuse "$reuse" --fill "$fill" \
      --report "$report" -q
    row=$(sed -n '/^| frames/{n;n;p;q}' "$report")
    IFS='|' read -r _ frames keys full acc saved_s saved mean minp exact rep traced interp _ <<<"$row"
    echo "| $name | $reuse | $fill |$frames|$full|$acc|$saved|$mean|$minp|$exact|$rep|$traced|" >> bench/animation_results.md
    echo "$name $reuse $fill:$saved% saved, mean PSNR$mean dB"
  done
done
