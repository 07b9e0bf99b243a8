#!/usr/bin/env bash
# An 8x6 Looking Glass quilt of the add-on tests' scene (tests/blender/scene.py),
# 420x560 px views, 40 degree view cone, focal plane at the camera's focus
# distance, side by side in one Blender process, alternating which goes
# first: the add-on (F12 with the quilt camera: export, holoray, loading
# back), Whitted and path traced, against Cycles rendering the 48 sheared
# views itself at the path tracing's samples and bounces (the camera
# moved along its x axis by D tan(phi_k) and its frame shifted back, as the
# quilt's views are; CYCLES_SAMPLES samples, no denoising). Wall seconds,
# ROUNDS rounds; writes bench/blender_quilt_results.md.
# Usage: bash bench/run_blender_quilt_bench.sh   (ROUNDS=3, CYCLES_SAMPLES=16)
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${ROUNDS:-3}
CYCLES_SAMPLES=${CYCLES_SAMPLES:-16}
source bench/lib.sh
command -v blender >/dev/null || { echo "run_blender_quilt_bench.sh: blender is not installed" >&2; exit 1; }
export BLENDER_USER_SCRIPTS=$PWD/build/blender PATH=$PWD/build:$PATH
cat > "$tmp/quilt.py" <<'PY'
import math, os, statistics, sys, time
import bpy
sys.path.insert(0, os.path.join(os.getcwd(), "tests", "blender"))
import scene as test_scene
rounds, samples = int(os.environ["ROUNDS"]), int(os.environ["CYCLES_SAMPLES"])
sc = test_scene.build()
h = sc.holoray
h.camera, h.quilt_columns, h.quilt_rows, h.view_width, h.view_height, h.view_cone = "QUILT", 8, 6, 420, 560, 40.0
cam = sc.camera
base, shift0 = cam.location.copy(), cam.data.shift_x
right = (cam.matrix_world.to_3x3() @ __import__("mathutils").Vector((1, 0, 0))).normalized()
D = cam.data.dof.focus_distance

BOUNCES = 4  # Cycles' bounces; holoray's ray depth is one more (the eye ray)

def holoray_quilt(integrator):
    sc.render.engine = "HOLORAY"
    h.camera = "QUILT"  # the resolution follows: 3360x3360
    h.integrator, h.samples, h.max_depth = integrator, samples if integrator == "PATH" else 1, BOUNCES + 1
    t = time.perf_counter()
    bpy.ops.render.render()
    return time.perf_counter() - t

def holoray_whitted():
    return holoray_quilt("WHITTED")

def holoray_path():
    return holoray_quilt("PATH")

def cycles_views():
    sc.render.engine = "CYCLES"
    c = sc.cycles
    # The fair settings of tests/blender/path_oracle.py: no clamping, glossy
    # blur, light threshold, adaptive stopping or denoiser; box filter; the
    # same bounces as holoray's path tracing.
    c.samples, c.use_adaptive_sampling, c.use_denoising = samples, False, False
    c.sample_clamp_direct = c.sample_clamp_indirect = c.blur_glossy = c.light_sampling_threshold = 0.0
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.transparent_max_bounces = BOUNCES
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = 420, 560, 100
    n = 48
    t = time.perf_counter()
    for k in range(n):
        phi = math.radians((k / (n - 1) - 0.5) * 40.0)
        x = D * math.tan(phi)
        larger = D * cam.data.sensor_width / cam.data.lens  # portrait: the height, AUTO fit
        cam.location = base + right * x
        cam.data.shift_x = shift0 - x / larger
        bpy.ops.render.render()
    elapsed = time.perf_counter() - t
    cam.location, cam.data.shift_x = base, shift0
    return elapsed

times = {holoray_whitted: [], holoray_path: [], cycles_views: []}
for r in range(rounds):
    order = list(times) if r % 2 == 0 else list(reversed(times))
    for f in order:
        times[f].append(f())
w, p, c = (times[f] for f in (holoray_whitted, holoray_path, cycles_views))
row = lambda xs: ' '.join(f'{x:.3f}' for x in xs)
print(f"QUILT {statistics.median(w):.3f} {statistics.median(p):.3f} {statistics.median(c):.3f} {row(w)} | {row(p)} | {row(c)}", flush=True)
PY
out=$(ROUNDS=$ROUNDS CYCLES_SAMPLES=$CYCLES_SAMPLES blender -b --factory-startup --python "$tmp/quilt.py" 2>&1 | grep '^QUILT ')
read -r _ whitted path cycles rest <<<"$out"
IFS='|' read -r whitted_rounds path_rounds cycles_rounds <<<"$rest"
{
  echo "# An 8x6 quilt in Blender: the holoray add-on against Cycles"
  echo
  echo "\`bash bench/run_blender_quilt_bench.sh\` (ROUNDS=$ROUNDS, CYCLES_SAMPLES=$CYCLES_SAMPLES) on $(machine), commit $(git describe --always --dirty)."
  echo
  echo "The add-on tests' scene as an 8x6 quilt of 420x560 views (3360x3360), 40 degree view cone, focal plane at the camera's"
  echo "focus distance, in one Blender process, the three in turn, alternating the order. Wall seconds, medians of the rounds:"
  echo
  echo "| renderer | s | rounds |"
  echo "|---|---:|---|"
  echo "| holoray add-on, Whitted (F12: export, one sample a pixel, loading back) | $whitted | $whitted_rounds |"
  echo "| holoray add-on, path tracing ($CYCLES_SAMPLES samples, ray depth 5) | $path | $path_rounds |"
  echo "| Cycles, the 48 sheared views rendered one by one ($CYCLES_SAMPLES samples, 4 bounces, fair settings) | $cycles | $cycles_rounds |"
  echo
  echo "Cycles / holoray path tracing, at equal samples and bounces: $(/usr/bin/python3 -c "print(f'{$cycles / $path:.2f}x')")."
  echo "Cycles / holoray Whitted: $(/usr/bin/python3 -c "print(f'{$cycles / $whitted:.1f}x')") (not the same light transport: hard shadows, no indirect light)."
} > bench/blender_quilt_results.md
cat bench/blender_quilt_results.md
