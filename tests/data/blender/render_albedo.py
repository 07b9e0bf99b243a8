"""Blender's albedo (the Cycles DiffCol pass) of each glTF scene here, as the
independent oracle for holoray's pinhole albedo AOV (tests/test_textures.cpp).
Made once, committed; CI does not need Blender.

    blender -b --factory-startup -P tests/data/blender/render_albedo.py

Debian's Blender 3.4: its glTF importer needs numpy.bool, which numpy has
dropped, and the denoiser is off so the pass is the samples' mean.
Each pixel is sampled near its centre (filter width 0.01 px), as holoray's
AOVs come from the pixel-centre sample. Writes NAME.albedo.exr (RGB, linear).
"""
import os
import sys

import bpy
import numpy

numpy.bool = bool  # Debian's Blender 3.4 glTF importer still uses it

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE = 128
SCENES = ["textured_box", "wrapped_box", "transform_box", "masked_leaf"]


def render(name):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.join(HERE, name + ".gltf"))
    scene = bpy.context.scene
    scene.camera = next(o for o in scene.objects if o.type == "CAMERA")
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = 16
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    if scene.world is None:
        scene.world = bpy.data.worlds.new("black")
    scene.world.color = (0, 0, 0)
    layer = scene.view_layers[0]
    layer.use_pass_diffuse_color = True
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    rl = tree.nodes.new("CompositorNodeRLayers")
    out = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["DiffCol"], out.inputs["Image"])
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    scene.render.filepath = os.path.join(HERE, name + ".albedo.exr")
    bpy.ops.render.render(write_still=True)


for name in SCENES:
    render(name)
sys.exit(0)
