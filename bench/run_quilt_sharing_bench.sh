#!/usr/bin/env bash
# A quilt's views sharing their path samples (--share-views), at equal
# noise, against Cycles rendering the 48 views one by one (the Looking Glass
# add-on's way). Two Blender scenes, each in one Blender process:
#   room   tests/blender/path_oracle.py's closed room lit by a square area
#          light (light bouncing off coloured walls: Monte Carlo noise);
#   addon  the add-on tests' scene of run_blender_quilt_bench.sh (a cube on
#          a plane under a sun and a point light, a black world).
# An 8x6 quilt of VIEW_W x VIEW_H views (40 degree cone). holoray through
# the add-on (F12, the Python module in Blender), path tracing at SAMPLES,
# then each SAMPLES:VIEWS pair of SHARED (samples a pixel, views shared on
# each side);
# Cycles' 48 views at SAMPLES with the fair settings, twice (seeds 0 and 1;
# its time the faster of the two).
# Noise is the 8-bit sRGB MSE: holoray's against its own quilt at
# REF_SAMPLES unshared, Cycles' as half the MSE between its two seeds (the
# two renderers converge to images about 38 dB apart, so neither is the
# other's reference). Wall seconds of each render, export and read-back
# included. Writes bench/quilt_sharing_results.md.
# Usage: bash bench/run_quilt_sharing_bench.sh
#   (SAMPLES=16, SHARED="8:4 4:8 3:12 2:16", VIEW_W=105, VIEW_H=140, REF_SAMPLES=256)
set -euo pipefail
cd "$(dirname "$0")/.."
SAMPLES=${SAMPLES:-16}
SHARED=${SHARED:-8:4 4:8 3:12 2:16}
VIEW_W=${VIEW_W:-105}
VIEW_H=${VIEW_H:-140}
REF_SAMPLES=${REF_SAMPLES:-256}
source bench/lib.sh
command -v blender >/dev/null || { echo "run_quilt_sharing_bench.sh: blender is not installed" >&2; exit 1; }
export BLENDER_USER_SCRIPTS=$PWD/build/blender PATH=$PWD/build:$PATH PYTHONPATH=$PWD/build/python
export SAMPLES SHARED VIEW_W VIEW_H REF_SAMPLES OUT=$tmp
blender -b --factory-startup --python tests/blender/path_oracle.py -- "$tmp/room" room 4 32 24 > /dev/null
cat > "$tmp/sharing.py" <<'PY'
import math, os, sys, time
import bpy
import mathutils
import numpy as np
import holoray

SAMPLES, W, H, REF = (int(os.environ[k]) for k in ("SAMPLES", "VIEW_W", "VIEW_H", "REF_SAMPLES"))
SHARED = [tuple(int(x) for x in pair.split(":")) for pair in os.environ["SHARED"].split()]
OUT, SCENE = os.environ["OUT"], sys.argv[sys.argv.index("--") + 1]
BOUNCES = 4  # Cycles' bounces; holoray's ray depth is one more (the eye ray)
if SCENE == "addon":
    sys.path.insert(0, os.path.join(os.getcwd(), "tests", "blender"))
    import scene as test_scene
    sc = test_scene.build()
else:
    sc = bpy.context.scene
    # The zero-parallax plane through the spheres: the outer views stay
    # inside the room's walls.
    sc.camera.data.dof.focus_distance = 7.5
from holoray_blender import placement
cam = sc.camera
sc.render.image_settings.file_format, sc.render.image_settings.color_depth = "OPEN_EXR", "32"


def srgb8(x):
    x = np.clip(x[:, :, :3], 0, 1)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055) * 255


def mse(a, b):
    return float(np.mean((srgb8(a) - srgb8(b)) ** 2))


def holoray_quilt(samples, share):
    sc.render.engine = "HOLORAY"
    h = sc.holoray
    h.camera, h.quilt_columns, h.quilt_rows, h.view_width, h.view_height, h.view_cone = "QUILT", 8, 6, W, H, 40.0
    h.integrator, h.samples, h.max_depth, h.share_views, h.backend = "PATH", samples, BOUNCES + 1, share, "MODULE"
    sc.render.filepath = os.path.join(OUT, "quilt.exr")
    t = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    seconds = time.perf_counter() - t
    return holoray.read_image(sc.render.filepath), seconds


def cycles_views(seed):
    sc.render.engine = "CYCLES"
    c = sc.cycles
    c.samples, c.seed, c.use_animated_seed = SAMPLES, seed, False
    c.use_adaptive_sampling, c.use_denoising = False, False
    c.sample_clamp_direct = c.sample_clamp_indirect = c.blur_glossy = c.light_sampling_threshold = 0.0
    c.pixel_filter_type, c.filter_width = "BOX", 1.0
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = c.transparent_max_bounces = BOUNCES
    sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = W, H, 100
    base, shift0 = cam.location.copy(), cam.data.shift_x
    right = (cam.matrix_world.to_3x3() @ mathutils.Vector((1, 0, 0))).normalized()
    D = placement.focus_distance(cam)
    larger = D * cam.data.sensor_width / cam.data.lens  # portrait: the height, AUTO fit
    views, t = [], time.perf_counter()
    for k in range(48):
        x = D * math.tan(math.radians((k / 47 - 0.5) * 40.0))
        cam.location = base + right * x
        cam.data.shift_x = shift0 - x / larger
        sc.render.filepath = os.path.join(OUT, f"view{k}.exr")
        bpy.ops.render.render(write_still=True)
        views.append(holoray.read_image(sc.render.filepath))
    seconds = time.perf_counter() - t
    cam.location, cam.data.shift_x = base, shift0
    return views, seconds


ref, ref_s = holoray_quilt(REF, 0)
rows = []
for samples, share in [(SAMPLES, 0)] + SHARED:
    img, s = holoray_quilt(samples, share)
    rows.append(("holoray", samples, share, s, mse(img, ref)))
a, sa = cycles_views(0)
b, sb = cycles_views(1)
noise = sum(mse(x, y) for x, y in zip(a, b)) / len(a) / 2
rows.append(("cycles", SAMPLES, 0, min(sa, sb), noise))  # the faster of the two: the machine's noise counts for Cycles
for r in rows:
    print("ROW", SCENE, *r, flush=True)
print("REF", SCENE, REF, ref_s, flush=True)
PY
blender -b "$tmp/room/scene.blend" --addons holoray_blender --python "$tmp/sharing.py" -- room 2>&1 | grep -E '^(ROW|REF) ' > "$tmp/rows"
blender -b --factory-startup --addons holoray_blender --python "$tmp/sharing.py" -- addon 2>&1 | grep -E '^(ROW|REF) ' >> "$tmp/rows"
/usr/bin/python3 - "$tmp/rows" "$(machine)" "$(git describe --always --dirty)" <<'PY' > bench/quilt_sharing_results.md
import math, os, sys
rows = [l.split() for l in open(sys.argv[1])]
env = {k: os.environ[k] for k in ("SAMPLES", "SHARED", "VIEW_W", "VIEW_H", "REF_SAMPLES")}
print("# Shared views at equal noise: holoray's quilt against Cycles' 48 views\n")
print(f"`bash bench/run_quilt_sharing_bench.sh` (SAMPLES={env['SAMPLES']}, SHARED=\"{env['SHARED']}\", "
      f"VIEW_W={env['VIEW_W']}, VIEW_H={env['VIEW_H']}, REF_SAMPLES={env['REF_SAMPLES']}) on {sys.argv[2]}, commit {sys.argv[3]}.\n")
print(f"An 8x6 quilt of {env['VIEW_W']}x{env['VIEW_H']} views, 40 degree cone, 4 bounces. Noise: 8-bit sRGB PSNR, holoray's "
      f"against its own quilt at {env['REF_SAMPLES']} samples unshared, Cycles' from the difference of two seeds. "
      "Wall seconds of the render in Blender (holoray: F12 through the add-on's Python module, export included; "
      "Cycles: the 48 views one by one, the faster of its two seeds' renders).\n")
for scene in ("room", "addon"):
    mine = [r for r in rows if r[0] == "ROW" and r[1] == scene]
    if not mine:
        continue
    print(f"## {'the area-lit room (path_oracle.py)' if scene == 'room' else 'the add-on tests scene (a cube on a plane, sun and point light)'}\n")
    print("| renderer | samples | shared views | seconds | noise PSNR dB |")
    print("|---|---:|---:|---:|---:|")
    for _, _, who, spp, share, sec, m in mine:
        print(f"| {who} | {spp} | {share} | {float(sec):.2f} | {10 * math.log10(255 ** 2 / float(m)):.2f} |")
    cyc = next(r for r in mine if r[2] == "cycles")
    cyc_s, cyc_m = float(cyc[5]), float(cyc[6])
    # Noise falls as 1/samples: the time each holoray row would take at
    # Cycles' noise. A row with less noise than Cycles' also gives a bound
    # that scales nothing: Cycles' time over its own.
    print()
    for r in mine:
        if r[2] != "holoray":
            continue
        at_equal = float(r[5]) * float(r[6]) / cyc_m
        measured = f"; {cyc_s / float(r[5]):.2f}x measured, with less noise" if float(r[6]) <= cyc_m else ""
        print(f"- holoray, {r[3]} samples, {r[4]} shared views: {cyc_s / at_equal:.2f}x Cycles' speed at Cycles' noise "
              f"({at_equal:.2f} s scaled by noise ~ 1/samples){measured}")
    print()
PY
cat bench/quilt_sharing_results.md
