"""One test case inside Blender: `blender -b --factory-startup --python case.py -- CASE OUT_DIR`.
Builds the tests' scene (scene.py), changes it as CASE says and saves it as
OUT_DIR/scene.blend, for the test to render as a user would (`blender -b
scene.blend -E HOLORAY -f 1`). The placement cases run the add-on's own
export and command here and print `RESULT {json}`."""

import json
import math
import os
import sys

import bpy

sys.path.insert(0, os.path.dirname(__file__))
import scene as test_scene  # noqa: E402

case, out = sys.argv[sys.argv.index("--") + 1:][:2]
sc = test_scene.build()
h = sc.holoray
binary = os.environ.get("HOLORAY_CLI", "")
h.lenses_x, h.lenses_y, h.pixels_per_lens = 24, 16, 5


def facing_plane(scale):
    """The camera looking along +y from (0, -5, 0), focused at 5, and a plane
    at y = 0 facing it, `scale` times the camera's field of view there."""
    for obj in list(sc.objects):
        if obj.type == "MESH":
            bpy.data.objects.remove(obj)
    cam = sc.camera
    cam.location = (0, -5, 0)
    cam.rotation_euler = (math.pi / 2, 0, 0)
    cam.data.dof.focus_distance = 5.0
    cam.data.sensor_fit = "AUTO"
    width = 5.0 * cam.data.sensor_width / cam.data.lens  # the view's width at 5 (landscape)
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(0, 0, 0), rotation=(math.pi / 2, 0, 0))
    plane = bpy.context.object
    plane.scale = (width * scale, width * scale, 1)
    return width


if case == "eia":
    pass
elif case in ("facing_plane_wide", "facing_plane_narrow"):
    # The add-on's own export and command, with the depth AOV read back: where
    # the array stands and what it spans.
    import subprocess
    import numpy as np
    from holoray_blender import engine, export
    facing_plane(1.05 if case.endswith("wide") else 0.8)
    h.aov_depth = True
    w, hgt = sc.render.resolution_x, sc.render.resolution_y
    gltf = export.export_gltf(out, sc, sc.camera)
    cmd, _ = engine.command(binary, sc, h, gltf, os.path.join(out, "eia.exr"), sc.camera, w, hgt)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t = engine.read_exr(os.path.join(out, "eia.depth.exr"), w, hgt)[:, 0].reshape(hgt, w)
    p = h.pixels_per_lens
    centres = t[p // 2::p, p // 2::p]  # each lens's centre pixel
    finite = np.isfinite(centres)
    print("RESULT " + json.dumps({"lenses_hit": int(finite.sum()), "lenses": int(finite.size),
                                  "max_abs_t": float(np.abs(centres[finite]).max()) if finite.any() else None,
                                  "edge_columns_hit": int(finite[:, [0, -1]].sum())}), flush=True)
    raise SystemExit(0)
elif case == "no_camera":
    bpy.data.objects.remove(sc.camera)
elif case == "empty":
    for obj in list(sc.objects):
        if obj.type == "MESH":
            bpy.data.objects.remove(obj)
elif case == "no_binary":
    pass  # rendered with a PATH that has no holoray
elif case == "large":
    h.lenses_x, h.lenses_y, h.pixels_per_lens = 256, 192, 16  # 4096x3072: long enough to cancel
else:
    raise SystemExit(f"unknown case {case}")

bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "scene.blend"))
print("RESULT " + json.dumps({"resolution": [sc.render.resolution_x, sc.render.resolution_y]}), flush=True)
