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


def f12_to_exr():
    """F12 with the holoray program, the EIA written as out/eia.exr (32-bit)."""
    bpy.context.preferences.addons["holoray_blender"].preferences.binary = binary
    sc.render.filepath = os.path.join(out, "eia.exr")
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    bpy.ops.render.render(write_still=True)


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
elif case == "cycles":
    # The add-on's pinhole view and the EIA's centre sub-aperture view, each
    # with its albedo, beside Cycles' diffuse colour pass (DiffCol) of the same
    # camera and of an orthographic camera where the array stands: written as
    # EXRs for the test to compare.
    import subprocess
    import numpy as np
    from holoray_blender import engine, export, placement
    cam = sc.camera

    def holoray_albedo(name, w, hgt, cameras):
        sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = w, hgt, 100
        gltf = export.export_gltf(out, sc, cam, cameras=cameras)
        cmd, _ = engine.command(binary, sc, h, gltf, os.path.join(out, name + ".exr"), cam, w, hgt)
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)

    def cycles_diffcol(name, w, hgt):
        sc.render.engine = "CYCLES"
        sc.cycles.samples = 4
        sc.cycles.filter_width = 0.01  # each pixel sampled at its centre, as holoray's first sample
        sc.cycles.use_denoising = False
        sc.view_layers[0].use_pass_diffuse_color = True
        sc.use_nodes = True
        tree = sc.node_tree
        tree.nodes.clear()
        layers, composite = tree.nodes.new("CompositorNodeRLayers"), tree.nodes.new("CompositorNodeComposite")
        tree.links.new(layers.outputs["DiffCol"], composite.inputs["Image"])
        sc.render.resolution_x, sc.render.resolution_y, sc.render.resolution_percentage = w, hgt, 100
        sc.render.image_settings.file_format = "OPEN_EXR"
        sc.render.image_settings.color_depth = "32"
        sc.render.filepath = os.path.join(out, name + ".exr")
        bpy.ops.render.render(write_still=True)
        sc.render.engine = "HOLORAY"
        sc.use_nodes = False

    h.aov_albedo = True
    cam.data.shift_x, cam.data.shift_y = 0.06, -0.04  # a lens shift: both framings follow it
    h.camera = "PINHOLE"
    holoray_albedo("pinhole", 160, 120, True)
    cycles_diffcol("pinhole_cycles", 160, 120)
    h.camera = "INTEGRAL"
    h.lenses_x, h.lenses_y, h.pixels_per_lens = 64, 48, 5
    holoray_albedo("eia", 320, 240, False)
    place = placement.array_placement(cam, 320 / 240)
    cam.data.type = "ORTHO"
    cam.data.ortho_scale = place.width
    cycles_diffcol("ortho_cycles", 64, 48)
    print("RESULT " + json.dumps({"array_width": place.width}), flush=True)
    raise SystemExit(0)
elif case == "animation":
    # The cube slides along x over frames 1 to 6; the output path is Blender's.
    cube = next(o for o in sc.objects if o.name.startswith("Cube"))
    sc.frame_start, sc.frame_end = 1, 6
    for frame, x in ((1, -0.6), (6, 0.6)):
        cube.location.x = x
        cube.keyframe_insert("location", frame=frame)
    sc.render.filepath = os.path.join(out, "render", "####")
    sc.render.image_settings.file_format = "PNG"
elif case == "preview":
    # F12, then the centre-view preview: the EIA's lens-centre pixels.
    import numpy as np
    f12_to_exr()
    bpy.ops.holoray.preview(kind="CENTRE")
    view = bpy.data.images["holoray preview"]
    eia = bpy.data.images.load(os.path.join(out, "eia.exr"))
    pixels = lambda img: np.array(img.pixels[:], dtype=np.float32).reshape(img.size[1], img.size[0], 4)
    p = h.pixels_per_lens
    centre = pixels(eia)[p // 2::p, p // 2::p, :3]
    print("RESULT " + json.dumps({"size": list(view.size),
                                  "max_difference": float(np.abs(pixels(view)[:, :, :3] - centre).max())}), flush=True)
    raise SystemExit(0)
elif case == "export_web":
    # F12, then the page: holoray web of the last EIA, the add-on's settings told.
    f12_to_exr()
    bpy.ops.holoray.export_web(directory=os.path.join(out, "page"))
    with open(os.path.join(out, "page", "light_field.json")) as f:
        manifest = json.load(f)
    print("RESULT " + json.dumps({"manifest": manifest, "files": sorted(os.listdir(os.path.join(out, "page")))}), flush=True)
    raise SystemExit(0)
elif case == "shot_placement":
    # The shot operator's array against F12's, with a lens shift: the first
    # key's `at` is the array's centre, `from` lies along its normal, and
    # its field of view spans the array's width.
    import re
    import numpy as np
    from holoray_blender import animation, job
    sc.camera.data.shift_x, sc.camera.data.shift_y = 0.06, -0.04
    w, hgt = sc.render.resolution_x, sc.render.resolution_y
    a = job.spec(sc, h, sc.camera, w, hgt)
    text = animation.shot_text(sc, sc.camera, 1, 1, 24)
    vec = lambda key: np.array([float(x) for x in re.search(key + r" = \[([^]]*)\]", text).group(1).split(",")])
    eye, at = vec("from"), vec("at")
    d = np.linalg.norm(eye - at)
    angle = float(re.search(r"angle = ([\d.eE+-]+)", text).group(1))
    width = 2 * d * np.tan(np.radians(angle) / 2)
    print("RESULT " + json.dumps({
        "centre": float(np.abs(at - np.array(a["origin"])).max()),
        "normal": float(np.abs((eye - at) / d - np.array(a["normal"])).max()),
        "width": float(abs(width - a["pitch"] * a["lenses"][0]))}), flush=True)
    raise SystemExit(0)
elif case == "panel":
    # What the holoray panel shows for each camera: its draw() on a layout
    # that records the settings it is asked to show.
    from holoray_blender import ui

    class Layout:
        def __init__(self, shown):
            self.shown, self.use_property_split = shown, False

        def prop(self, data, name, **kw):
            self.shown.append(name)

        def column(self, **kw):
            return self

        row = column

        def label(self, **kw):
            pass

        def operator(self, name, **kw):
            self.shown.append(name)
            return type("Op", (), {})()

    shown = {}
    for cam in ("INTEGRAL", "PINHOLE", "QUILT", "DISPLAY", "LOOKING_GLASS"):
        h.camera = cam
        shown[cam] = []
        panel = type("Panel", (), {"layout": Layout(shown[cam])})()
        ui.HOLORAY_PT_camera.draw(panel, bpy.context)
    print("RESULT " + json.dumps(shown), flush=True)
    raise SystemExit(0)
elif case == "untextured":
    # The cube's image texture unlinked (the GPU path reads no mesh textures yet).
    mat = bpy.data.materials["cube"]
    for link in list(mat.node_tree.links):
        if link.from_node.type == "TEX_IMAGE":
            mat.node_tree.links.remove(link)
elif case == "hex":
    h.grid = "HEX"
elif case == "quilt":
    h.camera = "QUILT"
    h.quilt_columns, h.quilt_rows, h.view_width, h.view_height = 4, 2, 60, 80
elif case == "no_camera":
    bpy.data.objects.remove(sc.camera)
elif case == "empty":
    for obj in list(sc.objects):
        if obj.type == "MESH":
            bpy.data.objects.remove(obj)
elif case == "no_binary":
    h.backend = "PROGRAM"  # rendered with a PATH that has no holoray
elif case == "both_ways":
    # Every pass, for the test to render once in Blender's process and once
    # through the program (backend set from the command line).
    h.aov_albedo = h.aov_depth = h.aov_normal = True
    sc.render.image_settings.file_format = "OPEN_EXR_MULTILAYER"
    sc.render.image_settings.color_depth = "32"
elif case == "bench":
    h.lenses_x, h.lenses_y, h.pixels_per_lens = 64, 64, 16  # 1024x1024 (bench/run_blender_bench.sh)
elif case in ("large", "large_module"):
    h.lenses_x, h.lenses_y, h.pixels_per_lens = 256, 192, 16  # 4096x3072: long enough to cancel
    h.backend = "PROGRAM" if case == "large" else "MODULE"
else:
    raise SystemExit(f"unknown case {case}")

bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "scene.blend"))
print("RESULT " + json.dumps({"resolution": [sc.render.resolution_x, sc.render.resolution_y]}), flush=True)
