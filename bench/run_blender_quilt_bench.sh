#!/usr/bin/env bash
# An 8x6 Looking Glass quilt of the add-on tests' scene (tests/blender/scene.py),
# 420x560 px views, 40 degree view cone, focal plane at the camera's focus
# distance, side by side in one Blender process, alternating which goes
# first: the add-on (F12 with the quilt camera: export, holoray, loading
# back) against Cycles rendering the 48 sheared views itself (the camera
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

def holoray_quilt():
    sc.render.engine = "HOLORAY"
    h.camera = "QUILT"  # the resolution follows: 3360x3360
    t = time.perf_counter()
    bpy.ops.render.render()
    return time.perf_counter() - t

def cycles_views():
    sc.render.engine = "CYCLES"
    sc.cycles.samples = samples
    sc.cycles.use_denoising = False
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

mine, theirs = [], []
for r in range(rounds):
    order = (holoray_quilt, cycles_views) if r % 2 == 0 else (cycles_views, holoray_quilt)
    for f in order:
        (mine if f is holoray_quilt else theirs).append(f())
m, c = statistics.median(mine), statistics.median(theirs)
print(f"QUILT {m:.3f} {c:.3f} {' '.join(f'{x:.3f}' for x in mine)} | {' '.join(f'{x:.3f}' for x in theirs)}", flush=True)
PY
out=$(ROUNDS=$ROUNDS CYCLES_SAMPLES=$CYCLES_SAMPLES blender -b --factory-startup --python "$tmp/quilt.py" 2>&1 | grep '^QUILT ')
read -r _ mine cycles rest <<<"$out"
{
  echo "# An 8x6 quilt in Blender: the holoray add-on against Cycles"
  echo
  echo "\`bash bench/run_blender_quilt_bench.sh\` (ROUNDS=$ROUNDS, CYCLES_SAMPLES=$CYCLES_SAMPLES) on $(machine), commit $(git describe --always --dirty)."
  echo
  echo "The add-on tests' scene as an 8x6 quilt of 420x560 views (3360x3360), 40 degree view cone, focal plane at the camera's"
  echo "focus distance, in one Blender process, alternating which goes first. Wall seconds, medians of the rounds:"
  echo
  echo "| renderer | s | rounds |"
  echo "|---|---:|---|"
  echo "| holoray add-on (F12: export, holoray's Whitted trace of every view, loading back) | $mine | ${rest%%|*}|"
  echo "| Cycles, the 48 sheared views rendered one by one ($CYCLES_SAMPLES samples, no denoising) | $cycles | ${rest#*| } |"
  echo
  echo "Cycles / holoray: $(/usr/bin/python3 -c "print(f'{$cycles / $mine:.1f}x')"). The two are not the same light transport: Cycles"
  echo "path traces (soft shadows, indirect light, noise at $CYCLES_SAMPLES samples), holoray ray traces as Whitted (one sample per pixel)."
} > bench/blender_quilt_results.md
cat bench/blender_quilt_results.md
