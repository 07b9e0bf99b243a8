"""Blender's framing of a file's camera, the reference for holoray's reading of
it: `blender -b --factory-startup --python file_camera.py -- FILE W H OUT.png [CAMERA]`.
Imports FILE with Blender's own importer for its format (or opens a .blend),
renders its active camera's view at W x H with Cycles, one sample at each
pixel's centre, on a transparent film, and writes the alpha (the silhouette)
as an 8-bit PNG. Prints `RESULT {json}`: the camera's name, type and angles."""

import json
import math
import os
import sys

import bpy
import numpy

# Blender 3.4's glTF importer calls numpy.bool, which numpy 1.24 (Debian 12's) removed.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

args = sys.argv[sys.argv.index("--") + 1:]
path, width, height, out = args[:4]
camera_name = args[4] if len(args) > 4 else ""
ext = os.path.splitext(path)[1].lower()
if ext == ".blend":
    bpy.ops.wm.open_mainfile(filepath=path)
else:
    bpy.ops.wm.read_factory_settings(use_empty=True)
    if ext in (".dae", ".zae"):
        if "collada_import" not in dir(bpy.ops.wm):  # Debian 13's Blender 4.3 is built without it
            print("SKIP Blender has no Collada importer")
            sys.exit(0)
        bpy.ops.wm.collada_import(filepath=path)
    elif ext == ".fbx":
        bpy.ops.import_scene.fbx(filepath=path)
    elif ext in (".gltf", ".glb"):
        bpy.ops.import_scene.gltf(filepath=path)
    else:
        raise SystemExit(f"no Blender importer for {ext}")

sc = bpy.context.scene
if camera_name:
    sc.camera = bpy.data.objects[camera_name]
elif sc.camera is None:  # Blender's importers set none: the file's first camera, as Blender's renderer takes
    cams = [o for o in sc.objects if o.type == "CAMERA"]
    sc.camera = cams[0]
cam = sc.camera
# Only the silhouette matters: lights, and objects the render leaves out, go.
for obj in list(sc.objects):
    if obj.type == "LIGHT":
        bpy.data.objects.remove(obj)
sc.render.engine = "CYCLES"
sc.cycles.samples = 1
sc.cycles.use_denoising = False
sc.cycles.filter_width = 0.01  # one sample at the pixel's centre, as holoray's pinhole
sc.cycles.max_bounces = 0
sc.render.film_transparent = True
sc.render.resolution_x, sc.render.resolution_y = int(width), int(height)
sc.render.resolution_percentage = 100
sc.render.pixel_aspect_x = sc.render.pixel_aspect_y = 1
sc.render.use_border = False
sc.render.image_settings.file_format = "PNG"
sc.render.image_settings.color_mode = "RGBA"
sc.render.filepath = out
bpy.ops.render.render(write_still=True)
d = cam.data
print("RESULT " + json.dumps({
    "camera": cam.name, "type": d.type, "angle_x_deg": math.degrees(d.angle_x), "angle_y_deg": math.degrees(d.angle_y),
    "sensor_fit": d.sensor_fit, "ortho_scale": d.ortho_scale, "clip": [d.clip_start, d.clip_end],
    "focus_distance": d.dof.focus_distance, "location": list(cam.matrix_world.translation)}))
