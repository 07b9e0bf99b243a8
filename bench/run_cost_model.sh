#!/usr/bin/env bash
# Measures how a still frame's trace time grows with each parameter of the
# cost model (docs/cost-model.md, issue 4): EIA size, lens count at a fixed
# EIA size, pixels per lens, primitive count and ray depth. Three or more
# points each; median of REPEATS runs of `holoray render`'s own trace time
# (parsing, BVH build and output excluded), all threads. Needs ../shared/scenes.
# Writes bench/cost_model.md. Usage: bash bench/run_cost_model.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shared=${HOLORAY_SHARED:-../shared}
[[ -d $shared/scenes/nff ]] || { echo "run_cost_model.sh: needs $shared/scenes/nff" >&2; exit 1; }
# Written to a temporary file first: a failed run leaves the last table as it was.
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
python3 - "$build/holoray" "$shared/scenes/nff" "${REPEATS:-3}" > "$tmp" <<'PY'
import os, re, statistics, subprocess, sys, tempfile
holoray, nff, repeats = sys.argv[1], sys.argv[2], int(sys.argv[3])
out = os.path.join(tempfile.mkdtemp(), "o.png")

def run(scene, lenses, p, extra=()):
    times, rays = [], 0
    for _ in range(repeats):
        text = subprocess.run([holoray, "render", f"{nff}/{scene}.nff", "-o", out, "--lenses", f"{lenses}x{lenses}",
                               "--pixels-per-lens", str(p), *extra], check=True, capture_output=True, text=True).stdout
        times.append(float(re.search(r"^trace\s+([0-9.]+) s", text, re.M).group(1)))
        rays = int(re.search(r"total (\d+)", text).group(1))
    return statistics.median(times), rays

def table(title, head, rows):
    print(f"### {title}\n")
    print("| " + " | ".join(head + ["trace (s)", "rays (M)", "ns per ray", "ns per pixel"]) + " |")
    print("|" + "---|" * len(head) + "---:|---:|---:|---:|")
    for cells, (t, rays), pixels in rows:
        print("| " + " | ".join(str(c) for c in cells) + f" | {t:.3f} | {rays / 1e6:.2f} | {t / rays * 1e9:.0f} | {t / pixels * 1e9:.0f} |")
    print()

rows = [((f"{l * 8}x{l * 8}", l), run("teapot_s6", l, 8), (l * 8) ** 2) for l in (64, 128, 256)]
table("EIA size (teapot_s6, 8 px per lens)", ["EIA (px)", "lenses across"], rows)
rows = [((f"{l}x{l}", 1024 // l), run("teapot_s6", l, 1024 // l), 1024 ** 2) for l in (256, 128, 64, 32)]
table("Lens count at a fixed 1024x1024 EIA (teapot_s6)", ["lenses", "px per lens"], rows)
rows = [((p, f"{64 * p}x{64 * p}"), run("teapot_s6", 64, p), (64 * p) ** 2) for p in (4, 8, 16, 32)]
table("Pixels per lens at 64x64 lenses (teapot_s6)", ["px per lens", "EIA (px)"], rows)
rows = []
for scene in ("balls_s1", "balls_s2", "balls_s3", "balls_s4", "teapot_s1", "teapot_s2", "teapot_s3", "teapot_s6"):
    text = subprocess.run([holoray, "render", f"{nff}/{scene}.nff", "-o", out, "--lenses", "8x8"], check=True,
                          capture_output=True, text=True).stdout
    count = int(re.search(r"^scene\s+.*?: (\d+) objects?", text, re.M).group(1))
    rows.append(((scene, count), run(scene, 128, 8), 1024 ** 2))
table("Primitive count at a 1024x1024 EIA (128x128 lenses x 8 px)", ["scene", "NFF objects"], rows)
rows = [((d,), run("balls_s4", 128, 8, ["--max-depth", str(d)]), 1024 ** 2) for d in (1, 2, 3, 5, 8)]
table("Ray depth (balls_s4: every sphere a mirror; 1024x1024 EIA)", ["max depth"], rows)
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
print(f"`bash bench/run_cost_model.sh`: {os.cpu_count()} threads on {cpu}; median of {repeats} runs of the trace time "
      "`holoray render` prints (packet style, orthoscopic square array).")
PY
mv "$tmp" bench/cost_model.md
cat bench/cost_model.md
