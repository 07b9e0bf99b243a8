#!/usr/bin/env bash
# Temporal reprojection benchmark (issue 3): every shot in bench/shots, once
# per method, each with --report (which also ray traces every frame in full,
# so the full and accelerated times come from the same run). Writes
# bench/animation_results.md (the Table 2 comparison) and the per-run reports
# in bench/animation_reports/, and plots them (bench/plot_animation.py).
# Needs ../shared beside the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/holoray
out=bench/animation_reports
mkdir -p "$out"
K=${K:-8}
# method, reuse, fill, cache. reproject: the paper's forward splat; reverse:
# eye rays traced, shading reused (no fill); full: every frame traced, with
# the shadow cache living across the frames (the cache's own row against the
# same run's full trace). METHODS="..." (one entry per line) runs only those.
default_methods="reverse color - off
reverse visibility - off
reproject color interpolate off
reproject geometry trace off
full - - on"
mapfile -t methods <<<"${METHODS:-$default_methods}"
{
  echo "# Temporal reprojection: time saved and quality (\`bash bench/run_animation_bench.sh\`)"
  echo
  echo "Machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); keyframe interval $K; full-ray-tracing time measured in the same run (--report)."
  echo
  echo "Hold = the do-nothing baseline: each reprojected frame replaced by its nearest keyframe, scored against the same full trace. Rebuilt: frames whose holes exceeded --rebuild-above (5 %) and were traced, not interpolated."
  echo
  echo "Reverse: every eye ray traced (so nothing is missed), a hit's shading reused from the keyframe pixel that saw it (color: its colour; visibility: its light visibility and mirror/refraction light, ambient, diffuse and highlights computed exactly, edges traced). Reprojected % = pixels reused; traced % = pixels shaded or background."
  echo
  echo "| shot | method | reuse | fill | cache | frames | full s | accelerated s | saved % | mean PSNR dB | min PSNR dB | hold mean PSNR dB | hold min PSNR dB | frames below hold | rebuilt | reprojected % | traced % |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} > bench/animation_results.md
# SHOTS="teapot tree" runs only those (default: every shot in bench/shots).
for name in ${SHOTS:-$(basename -s .toml bench/shots/*.toml)}; do
  shot=bench/shots/$name.toml
  for m in "${methods[@]}"; do
    read -r method reuse fill cache <<<"$m"
    if [ "$method" = full ]; then
      report="$out/${name}_full_cache.md"
      args=(--method full --cache "$cache")
    elif [ "$method" = reverse ]; then
      report="$out/${name}_reverse_${reuse}.md"
      args=(--method reverse --keyframe-interval "$K" --reuse "$reuse" --cache "$cache")
    else
      report="$out/${name}_${reuse}_${fill}.md"
      args=(--method reproject --keyframe-interval "$K" --reuse "$reuse" --fill "$fill" --cache "$cache")
    fi
    "$bin" animate "$shot" -o "/tmp/holoray_bench_$name" "${args[@]}" --report "$report" -q
    row=$(sed -n '/^| frames/{n;n;p;q}' "$report")
    IFS='|' read -r _ frames keys full acc saved_s saved mean minp hmean hmin below rebuilt exact rep traced interp _ <<<"$row"
    echo "| $name | $method | $reuse | $fill | $cache |$frames|$full|$acc|$saved|$mean|$minp|$hmean|$hmin|$below|$rebuilt|$rep|$traced|" >> bench/animation_results.md
    echo "$name $method $reuse $fill cache $cache:$saved% saved, mean PSNR$mean dB (hold$hmean dB)"
  done
done
# Per-shot plots of PSNR and seconds per frame (bench/plots/*.svg).
if command -v python3 >/dev/null; then python3 bench/plot_animation.py; fi
