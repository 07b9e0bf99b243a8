#!/usr/bin/env bash
# PNG compression against real EIAs: renders the four SPD scenes' 2048x2048
# EIAs (128x128 lenses x 16 px) once, then times PNG writing with each zlib
# level, strategy and row filter (bench/png_encode.cpp, Google Benchmark,
# median of REPETITIONS runs) and records the file sizes. Writes
# bench/png_results.md. Needs ../shared. Usage: bash bench/run_png_bench.sh
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/lib.sh
bench_targets build holoray_png_encode
reps=${REPETITIONS:-5}
scenes=(teapot_s6 gears_s4 balls_s4 tree_s11)
files=()
for s in "${scenes[@]}"; do
  files+=("$tmp/$s.exr")
  "$bin" render "../shared/scenes/nff/$s.nff" --lenses 128x128 --pixels-per-lens 16 -o "$tmp/$s.exr" -q
done
build/bench/holoray_png_encode --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_format=csv "${files[@]}" 2>/dev/null | sed "s|$tmp/||g; s|\.exr||g" > "$tmp/png.csv"
python3 - "$tmp/png.csv" "$(machine)" "$reps" > bench/png_results.md <<'PY'
import csv, sys
rows = [r for r in csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith(('Run on', 'CPU', '  L', 'Load')))]
med = {r['name'].rsplit('_median', 1)[0]: r for r in rows if r['name'].endswith('_median')}
scenes = sorted({k.split('/')[0] for k in med}, key=lambda s: list(med).index(next(k for k in med if k.startswith(s + '/'))))
settings = [k.split('/')[1] for k in med if k.startswith(scenes[0] + '/')]
print('# PNG compression of 2048x2048 EIAs\n')
print(f'`bash bench/run_png_bench.sh` on {sys.argv[2]}: each setting writes each EIA to a PNG file, '
      f'median of {sys.argv[3]} runs (ms), and the file size as a share of the raw 8-bit RGB (12 MiB).\n')
print('| setting | ' + ' | '.join(f'{s} ms | {s} size' for s in scenes) + ' |')
print('|---|' + '---:|---:|' * len(scenes))
for st in settings:
    cells = []
    for s in scenes:
        r = med[f'{s}/{st}']
        cells += [f"{float(r['real_time']):.1f}", f"{float(r['of_raw']) * 100:.1f} %"]
    print(f'| {st} | ' + ' | '.join(cells) + ' |')
PY
cat bench/png_results.md
