"""Cycles as the oracle for holoray's path integrator.

    blender -b --factory-startup --python tests/blender/path_oracle.py -- OUTDIR SCENE SAMPLES WIDTH HEIGHT [RENDERED]

SCENE is `hdri` (the world is Blender's bundled courtyard.exr), `sky` (a
constant-colour world), `room` (a closed room with a red and a green wall,
lit by one square area light) or `sun` (the spheres on the floor under a sun
of 6 degrees and a point light of radius 0.25, a black world). Builds the
scene from nothing, renders it with Cycles on the CPU with every
bias-introducing shortcut switched off, and writes OUTDIR/cycles.exr
(linear float RGB), OUTDIR/scene.gltf (the same scene through Blender's own
glTF exporter, for holoray to load), OUTDIR/lights.toml (its lights, written
by the add-on's own lighting.write_lights), OUTDIR/scene.blend (for the
add-on's render) and OUTDIR/oracle.json (what was rendered and how long it
took). RENDERED: an EXR this script's Cycles render wrote before for the
same scene, settings and Blender (test_path_vs_cycles.py's cache), copied
as OUTDIR/cycles.exr instead of rendering again; the scene is still built,
exported and saved here. Written for
Blender 3.4 (Debian's); the Blender 4 input names are tried too, but that is
untested.
"""

import json
import math
import os
import shutil
import sys
import time

import bpy
from mathutils import Vector

# The add-on's lights file writer: the oracle's lights reach holoray as the
# add-on sends them.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "blender"))
from holoray_blender import lighting  # noqa: E402

ENVIRONMENT = "/usr/share/blender/datafiles/studiolights/world/courtyard.exr"
SKY_COLOUR = (0.6, 0.7, 0.9)
BOUNCES = 4


def set_input(node, names, value):
    """Sets the first of `names` the node has: Blender 4 renamed several of
    the Principled BSDF's inputs (Specular, Sheen, Clearcoat...)."""
    for name in names:
        if name in node.inputs:
            node.inputs[name].default_value = value
            return
    raise KeyError(f"{node.name} has none of {names}")


def principled(name, colour, roughness, metallic, specular=0.5):
    """A Principled BSDF reduced to what holoray models: plain GGX (the
    multiscatter variant adds energy holoray does not) and none of the
    subsurface, sheen or clearcoat lobes."""
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    bsdf.distribution = "GGX"
    set_input(bsdf, ["Base Color"], (*colour, 1.0))
    set_input(bsdf, ["Roughness"], roughness)
    set_input(bsdf, ["Metallic"], metallic)
    set_input(bsdf, ["Specular", "Specular IOR Level"], specular)
    set_input(bsdf, ["Subsurface", "Subsurface Weight"], 0.0)
    set_input(bsdf, ["Sheen", "Sheen Weight"], 0.0)
    set_input(bsdf, ["Clearcoat", "Coat Weight"], 0.0)
    return mat


def sphere(name, location, mat):
    # 64x32 so that the faceting is far below a pixel at the test sizes and
    # both renderers see the same smooth-shaded tessellation in the glTF.
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.8, location=location)
    obj = bpy.context.active_object
    obj.name = obj.data.name = name  # the glTF's mesh names then say which is which
    bpy.ops.object.shade_smooth()
    obj.data.materials.append(mat)


def build(scene_name):
    scene = bpy.context.scene
    # --factory-startup still leaves the default cube, light and camera; the
    # light in particular would light the scene beside the world.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for coll in (bpy.data.meshes, bpy.data.lights, bpy.data.cameras, bpy.data.materials):
        for block in list(coll):
            coll.remove(block)

    bpy.ops.mesh.primitive_plane_add(size=10.0, location=(0, 0, 0))
    floor = bpy.context.active_object
    floor.name = floor.data.name = "floor"
    floor.data.materials.append(principled("floor", (0.5, 0.5, 0.5), 1.0, 0.0))
    sphere("clay", (-1.0, 0, 0.8), principled("clay", (0.8, 0.45, 0.3), 0.9, 0.0))
    sphere("metal", (1.1, 0, 0.8), principled("metal", (0.9, 0.9, 0.9), 0.35, 1.0))
    if scene_name == "room":
        # Walls 6 wide and 4 high around the spheres, the front one behind
        # the camera; their normals face in.
        walls = {"back": ((0, 3, 2), (math.pi / 2, 0, 0), (0.7, 0.7, 0.7)),
                 "front": ((0, -8, 2), (-math.pi / 2, 0, 0), (0.7, 0.7, 0.7)),
                 "left": ((-3, -2.5, 2), (0, math.pi / 2, 0), (0.7, 0.1, 0.1)),
                 "right": ((3, -2.5, 2), (0, -math.pi / 2, 0), (0.1, 0.7, 0.1)),
                 "ceiling": ((0, -2.5, 4), (math.pi, 0, 0), (0.7, 0.7, 0.7))}
        for name, (loc, rot, colour) in walls.items():
            bpy.ops.mesh.primitive_plane_add(size=11.0, location=loc, rotation=rot)
            wall = bpy.context.active_object
            wall.name = wall.data.name = name
            wall.data.materials.append(principled(name, colour, 1.0, 0.0))
        area = bpy.data.lights.new("area", "AREA")
        area.shape, area.size, area.energy = "SQUARE", 1.2, 400.0
        light = bpy.data.objects.new("area", area)
        light.location = (0, -0.5, 3.9)  # under the ceiling, facing down (its local -Z)
        scene.collection.objects.link(light)
    if scene_name == "sun":
        sun = bpy.data.lights.new("sun", "SUN")
        sun.energy, sun.angle = 3.0, math.radians(6.0)
        obj = bpy.data.objects.new("sun", sun)
        obj.rotation_euler = (math.radians(40), 0, math.radians(30))
        scene.collection.objects.link(obj)
        point = bpy.data.lights.new("point", "POINT")
        point.energy, point.shadow_soft_size = 300.0, 0.25
        obj = bpy.data.objects.new("point", point)
        obj.location = (-2.0, -1.5, 2.5)
        scene.collection.objects.link(obj)

    cam_data = bpy.data.cameras.new("camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "AUTO"
    # With AUTO the angle spans the larger image side: horizontal for the
    # landscape sizes the tests use.
    cam_data.angle = math.radians(40.0)
    cam = bpy.data.objects.new("camera", cam_data)
    scene.collection.objects.link(cam)
    cam.location = (0.0, -7.0, 3.2)
    # A baked rotation rather than a Track To constraint, so that the glTF
    # exporter sees the same orientation as the renderer without evaluating
    # constraints.
    cam.rotation_mode = "QUATERNION"
    cam.rotation_quaternion = (Vector((0.0, 0.0, 0.6)) - cam.location).to_track_quat("-Z", "Y")
    scene.camera = cam

    # A fresh world: the factory one is a dim grey that would do for `sky`
    # only by accident.
    world = bpy.data.worlds.new(scene_name)
    world.use_nodes = True
    scene.world = world
    nodes, links = world.node_tree.nodes, world.node_tree.links
    background = nodes["Background"]
    background.inputs["Strength"].default_value = 1.0
    if scene_name in ("room", "sun"):
        background.inputs["Color"].default_value = (0, 0, 0, 1)
    elif scene_name == "hdri":
        env = nodes.new("ShaderNodeTexEnvironment")
        env.image = bpy.data.images.load(ENVIRONMENT, check_existing=True)
        # Blender loads an EXR as scene-linear already; naming it keeps a
        # changed OCIO default from converting it (Blender 4 renamed Linear).
        spaces = env.image.colorspace_settings.bl_rna.properties["name"].enum_items.keys()
        env.image.colorspace_settings.name = "Linear" if "Linear" in spaces else "Linear Rec.709"
        env.projection = "EQUIRECTANGULAR"
        env.interpolation = "Linear"
        links.new(env.outputs["Color"], background.inputs["Color"])
    else:
        background.inputs["Color"].default_value = (*SKY_COLOUR, 1.0)
    return scene


def fair_settings(scene, samples, width, height):
    """Cycles with its biased shortcuts off, so that the two renderers
    should agree within noise: no clamping, no glossy blur, no light
    threshold, no denoiser and no adaptive stopping; a one-pixel box filter,
    which is holoray's pixel footprint; the same bounce limit everywhere."""
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = samples
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.light_sampling_threshold = 0.0
    # Blender 3.x calls it pixel_filter_type; filter_type is the old name.
    if hasattr(c, "filter_type"):
        c.filter_type = "BOX"
    else:
        c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.max_bounces = BOUNCES
    c.diffuse_bounces = BOUNCES
    c.glossy_bounces = BOUNCES
    c.transmission_bounces = BOUNCES
    c.transparent_max_bounces = BOUNCES
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.seed = 0
    c.use_animated_seed = False

    # Standard/None/0/1 make the view transform an identity; the EXR is
    # written scene-linear regardless, but the settings keep any preview
    # honest too.
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    r = scene.render
    r.resolution_x, r.resolution_y = width, height
    r.resolution_percentage = 100
    r.film_transparent = False
    r.dither_intensity = 0.0
    r.use_compositing = False
    r.use_sequencer = False
    r.image_settings.file_format = "OPEN_EXR"
    r.image_settings.color_mode = "RGB"
    r.image_settings.color_depth = "32"
    r.image_settings.exr_codec = "ZIP"


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    if len(args) not in (5, 6) or args[1] not in ("hdri", "sky", "room", "sun"):
        sys.exit("usage: blender -b --factory-startup --python path_oracle.py -- "
                 "OUTDIR hdri|sky|room|sun SAMPLES WIDTH HEIGHT [RENDERED]")
    out, scene_name = os.path.abspath(args[0]), args[1]
    samples, width, height = (int(a) for a in args[2:5])
    rendered = args[5] if len(args) == 6 else None
    os.makedirs(out, exist_ok=True)

    scene = build(scene_name)
    fair_settings(scene, samples, width, height)

    scene.render.filepath = os.path.join(out, "cycles.exr")
    start = time.monotonic()
    if rendered:
        shutil.copyfile(rendered, os.path.join(out, "cycles.exr"))
    else:
        bpy.ops.render.render(write_still=True)
    seconds = time.monotonic() - start

    # Blender's own exporter, so that holoray is tested on what a Blender
    # user would hand it: +Y up, modifiers applied, the camera included.
    bpy.ops.export_scene.gltf(filepath=os.path.join(out, "scene.gltf"), export_format="GLTF_SEPARATE",
                              export_cameras=True, export_lights=False, export_apply=True,
                              export_yup=True)

    lighting.write_lights(scene, os.path.join(out, "lights.toml"))
    bpy.ops.wm.save_as_mainfile(filepath=os.path.join(out, "scene.blend"))

    with open(os.path.join(out, "oracle.json"), "w") as f:
        json.dump({"scene": scene_name, "samples": samples, "width": width, "height": height,
                   "environment": ENVIRONMENT if scene_name == "hdri" else None,
                   "colour": list(SKY_COLOUR) if scene_name == "sky" else ([0, 0, 0] if scene_name in ("room", "sun") else None),
                   "max_bounces": BOUNCES, "seconds": round(seconds, 3), "rendered_before": rendered}, f, indent=2)
    how = f"copied from {rendered}" if rendered else f"in {seconds:.2f} s"
    print(f"path_oracle: {scene_name} {width}x{height} {samples} spp {how} -> {out}")


main()
