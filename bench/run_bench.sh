#!/usr/bin/env bash
# The still-renderer benchmark suite (issues 2 and 4); needs ../shared/scenes.
# Writes bench/results.md, every figure measured in this one run:
#   1. primary visibility per style against plain Embree on the same rays
#      (rtcIntersect1 and rtcIntersect16 packets), Google Benchmark medians;
#   2. a full Whitted frame in each pixel-tracing style, and the paper's
#      Table 3 (the first lens);
#   3. median of REPEATS runs: holoray rendering a 2048x2048 EIA against
#      Tachyon and POV-Ray 3.7 rendering the same NFF scene as an ordinary
#      2048x2048 image, same threads, ray depth 5, no anti-aliasing (POV-Ray
#      reads a conversion, bench/nff_to_pov.py); the render time each reports,
#      and the wall clock of the whole command;
#   4. thread scaling of holoray's render, 1 thread against all;
#   5. Mrays/s by ray kind (eye, shadow, mirror) at three EIA sizes;
#   6. full tracing at 512x512, 1024x1024 and 2048x2048;
#   7. temporal reuse over whole shots (bench/run_animation_bench.sh, also
#      writing bench/animation_results.md; SKIP_TEMPORAL=1 leaves it out).
# Usage: bash bench/run_bench.sh [build-dir]   (REPEATS=3, THREADS=nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shared=${HOLORAY_SHARED:-../shared}
[[ -d $shared/scenes/nff ]] || { echo "run_bench.sh: needs $shared/scenes/nff" >&2; exit 1; }
for tool in tachyon povray; do
  command -v "$tool" >/dev/null || { echo "run_bench.sh: '$tool' is missing (bash scripts/setup.sh installs it)" >&2; exit 1; }
done
source bench/lib.sh
bench_targets "$build" holoray_bench
json=$(mktemp)
work=$(mktemp -d)
trap 'rm -rf "$json" "$work" "$tmp"' EXIT
"$build/bench/holoray_bench" --benchmark_report_aggregates_only=true \
  --benchmark_out="$json" --benchmark_out_format=json >/dev/null
python3 - "$json" "$build/holoray" "$shared" "$work" "${REPEATS:-3}" "${THREADS:-$(nproc)}" > "$work/results.md" <<'PY'
import json, os, re, statistics, subprocess, sys, time
data_path, holoray, shared, work, repeats, threads = sys.argv[1:7]
repeats, threads = int(repeats), int(threads)
scenes = ("balls_s4", "gears_s4", "teapot_s6", "tree_s11")
data = json.load(open(data_path))
med = {}
for b in data["benchmarks"]:
    if b.get("aggregate_name") == "median":
        kind, scene = b["run_name"].split("/")[:2]
        med[(kind, scene)] = b
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
rate = lambda k, s: med[(k, s)]["rays"] / 1e6
secs = lambda k, s: med[(k, s)]["real_time"] / 1e3  # ms -> s

print("### Primary visibility (Mrays/s; ray generation, clipping, trace and double-precision refinement)\n")
print("| scene | packet style | single rays | plain Embree rtcIntersect1 | plain Embree rtcIntersect16 | packet / rtcIntersect16 | packet / rtcIntersect1 |")
print("|---|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    p, h, r1, r16 = (rate(k, s) for k in ("IntegralPrimary_packet", "IntegralPrimary_horizontal", "EmbreeRaw", "EmbreePacket"))
    print(f"| {s} | {p:.1f} | {h:.1f} | {r1:.1f} | {r16:.1f} | {p / r16:.2f} | {p / r1:.2f} |")

print("\n### A full Whitted frame (s) in each pixel-tracing style, and the paper's Table 3 (first lens, us)\n")
print("| scene | packet | horizontal | vertical | packet speed-up | first lens: packet | horizontal | vertical |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    p, h, v = (secs("FullShading_" + st, s) for st in ("packet", "horizontal", "vertical"))
    fl = [med[("FirstLens_" + st, s)]["real_time"] for st in ("packet", "horizontal", "vertical")]
    print(f"| {s} | {p:.3f} | {h:.3f} | {v:.3f} | {h / p:.2f}x | {fl[0]:.1f} | {fl[1]:.1f} | {fl[2]:.1f} |")

def wall(cmd, trace_pattern):
    """Median wall time of the whole command, and of the render time it reports itself."""
    times, traces = [], []
    for _ in range(repeats):
        t = time.perf_counter()
        r = subprocess.run(cmd, check=True, capture_output=True, text=True, errors="replace", cwd=work)
        times.append(time.perf_counter() - t)
        traces.append(float(re.search(trace_pattern, r.stdout + r.stderr, re.M).group(1)))
    return statistics.median(times), statistics.median(traces)

print(f"\n### Against Tachyon and POV-Ray at 2048x2048 pixels, {threads} threads (s, median of {repeats})\n")
print("Render: the time each program reports for rendering alone (holoray `trace`, Tachyon `Ray Tracing Time`, "
      "POV-Ray `Trace Time`). Whole: wall clock of the whole command (reading, BVH build, rendering, writing the PNG).\n")
print("| scene | holoray render | Tachyon render | POV-Ray render | Tachyon / holoray | POV-Ray / holoray | holoray whole | Tachyon whole | POV-Ray whole | holoray 1 thread, render | thread scaling |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    nff = os.path.abspath(f"{shared}/scenes/nff/{s}.nff")
    pov = os.path.join(work, s + ".pov")
    with open(pov, "w") as f:
        subprocess.run([sys.executable, os.path.join(os.getcwd(), "bench/nff_to_pov.py"), nff], check=True, stdout=f, stderr=subprocess.DEVNULL)
    ours_cmd = [os.path.abspath(holoray), "render", nff, "-o", "h.png", "--lenses", "128x128", "--pixels-per-lens", "16"]
    ours_pat = r"^trace\s+([0-9.]+) s"
    ours, ours_r = wall(ours_cmd + ["--threads", str(threads)], ours_pat)
    _, ours1_r = wall(ours_cmd + ["--threads", "1"], ours_pat)
    tach, tach_r = wall(["tachyon", nff, "-res", "2048", "2048", "-numthreads", str(threads), "-raydepth", "5", "-aasamples", "0",
                         "-format", "PNG", "-o", "t.png"], r"Ray Tracing Time:\s+([0-9.]+)")
    povr, povr_r = wall(["povray", "+I" + pov, "+Op.png", "+W2048", "+H2048", f"+WT{threads}", "-D", "-V", "+FN"],
                        r"Trace Time:.*\(([0-9.]+) seconds\)")
    print(f"| {s} | {ours_r:.2f} | {tach_r:.2f} | {povr_r:.2f} | {tach_r / ours_r:.2f}x | {povr_r / ours_r:.2f}x | "
          f"{ours:.2f} | {tach:.2f} | {povr:.2f} | {ours1_r:.2f} | {ours1_r / ours_r:.2f}x |")

print("\n### Mrays/s by ray kind and EIA size (16 px per lens), Google Benchmark medians\n")
print("Each kind traced alone, as the renderer traces it: eye rays in the packet style (generation, clipping, "
      "trace, refinement); the shadow rays of the eye rays' hits, 16-ray packets toward one light "
      "(rtcOccluded16); the same shadow rays regrouped over the whole frame into packets of one light with "
      "neighbouring origins (sorted by Morton code; the sort not timed: the ceiling of queuing a frame's shadow "
      "rays before tracing them); the mirror rays of the hits on mirrors, one by one, incoherent, refined. "
      "The share of each kind is that of a whole Whitted frame at that size (`holoray render`, all depths).\n")
print("| scene | EIA | eye | shadow | shadow, sorted | mirror | frame rays: eye | shadow | reflected + refracted |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
for s in scenes:
    nff = os.path.abspath(f"{shared}/scenes/nff/{s}.nff")
    for lenses in (32, 64, 128):
        w = 16 * lenses
        r = subprocess.run([os.path.abspath(holoray), "render", nff, "-o", "kinds.png", "--lenses", f"{lenses}x{lenses}",
                            "--pixels-per-lens", "16"], check=True, capture_output=True, text=True, cwd=work)
        m = re.search(r"^rays\s+eye (\d+), shadow (\d+), reflected (\d+), refracted (\d+)", r.stdout, re.M)
        eye, shadow, refl, refr = (int(x) for x in m.groups())
        total = eye + shadow + refl + refr
        mirror = f"{rate(f'Kind{w}_mirror', s):.1f}" if (f"Kind{w}_mirror", s) in med else "(no mirrors)"
        print(f"| {s} | {w}x{w} | {rate(f'Kind{w}_eye', s):.1f} | {rate(f'Kind{w}_shadow', s):.1f} | "
              f"{rate(f'Kind{w}_shadow_sorted', s):.1f} | {mirror} | "
              f"{100 * eye / total:.0f}% | {100 * shadow / total:.0f}% | {100 * (refl + refr) / total:.0f}% |")

print(f"\n### Full tracing by EIA size, 16 px per lens, {threads} threads (render s, median of {repeats})\n")
print("| scene | EIA | full | Mrays/s |")
print("|---|---|---:|---:|")
for s in scenes:
    nff = os.path.abspath(f"{shared}/scenes/nff/{s}.nff")
    for lenses in (32, 64, 128):
        base = [os.path.abspath(holoray), "render", nff, "--lenses", f"{lenses}x{lenses}", "--pixels-per-lens", "16",
                "--threads", str(threads)]
        pat = r"^trace\s+([0-9.]+) s"
        _, full = wall(base + ["-o", "full.exr"], pat)
        r = subprocess.run(base + ["-o", "full.exr"], check=True, capture_output=True, text=True, cwd=work)
        mrays = re.search(r"([0-9.]+) Mrays/s", r.stdout).group(1)
        cells = [f"{16 * lenses}x{16 * lenses}", f"{full:.3f}", mrays]
        print(f"| {s} | " + " | ".join(cells) + " |")

print(f"\n{threads} threads on {cpu} ({os.cpu_count()} cores); Google Benchmark medians of 3 repetitions; "
      f"{data['context'].get('date', '')}.")
PY
# Temporal reuse, in the same run: the animation benchmark (issue 3).
if [[ ${SKIP_TEMPORAL:-0} != 1 ]]; then
  bash bench/run_animation_bench.sh >/dev/null
  {
    echo
    echo "### Temporal reuse: whole shots, reprojected between keyframes against full ray tracing (bench/run_animation_bench.sh)"
    echo
    sed -n '/^| shot/,$p' bench/animation_results.md
  } >> "$work/results.md"
fi
mv "$work/results.md" bench/results.md
cat bench/results.md
