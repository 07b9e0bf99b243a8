#!/usr/bin/env bash
# Runs the still-renderer benchmark (needs ../shared/scenes) and writes
# bench/results.md: per SPD scene at 128x128 lenses x 16 px (2048x2048),
# medians of 3 repetitions. Usage: bash bench/run_bench.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
json=$(mktemp)
"$build/bench/holoray_bench" --benchmark_report_aggregates_only=true \
  --benchmark_out="$json" --benchmark_out_format=json >/dev/null
python3 - "$json" > bench/results.md <<'PY'
import json, sys, platform, os
data = json.load(open(sys.argv[1]))
med = {}
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    kind, scene = b["run_name"].split("/")[:2]
    med[(kind, scene)] = b
ctx = data["context"]
cpu = "unknown CPU"
try:
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu = line.split(":", 1)[1].strip()
            break
except OSError:
    pass
print("| scene | integral camera primary (Mrays/s) | plain Embree rtcIntersect1, same rays (Mrays/s) | ratio | full Whitted shading (s/frame) | all rays (Mrays/s) |")
print("|---|---:|---:|---:|---:|---:|")
for scene in ("balls_s4", "gears_s4", "teapot_s6", "tree_s11"):
    ip, er, fs = med.get(("IntegralPrimary", scene)), med.get(("EmbreeRaw", scene)), med.get(("FullShading", scene))
    if not (ip and er and fs):
        continue
    a, b = ip["rays"] / 1e6, er["rays"] / 1e6
    print(f"| {scene} | {a:.2f} | {b:.2f} | {a / b:.2f} | {fs['real_time'] / 1e3:.2f} | {fs['rays'] / 1e6:.2f} |")
print()
print(f"2048x2048 EIA (128x128 lenses x 16 px, square, orthoscopic), medians of 3 runs; "
      f"{ctx.get('num_cpus')} threads on {cpu}; {ctx.get('date', '')}.")
PY
rm -f "$json"
cat bench/results.md
