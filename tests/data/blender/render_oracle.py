"""Blender's renders of each glTF scene here, the independent oracle for
holoray (tests/test_textures.cpp, tests/test_gltf_shading.cpp). Made once,
committed; CI does not need Blender.

    blender -b --factory-startup -P tests/data/blender/render_oracle.py

Writes, linear RGB OpenEXR:
  NAME.albedo.exr  Cycles' DiffCol pass (every scene), for the albedo AOV;
  NAME.direct.exr  DiffDir x DiffCol + GlossDir x GlossCol (the lit scenes):
                   the light that reaches the camera after one bounce off a
                   surface straight from a light, for holoray's shaded image;
  NAME.fF.albedo.exr  DiffCol at frame F of an animated scene (Blender's
                   importer keys glTF time t at frame t x 24, the fps of the
                   scene it imports into).

Debian's Blender 3.4: its glTF importer needs numpy.bool, which numpy has
dropped, and the denoiser is off so the passes are the samples' mean.
Each pixel is sampled near its centre (filter width 0.01 px), as holoray's
pixels are. glTF's lights are punctual: the importer's point and spot lights
get radius 0 and its sun an angle of 0 (Blender gives new lights a size).
The Principled BSDF is set to single-scattering GGX, glTF's Appendix B
distribution (Blender 3.4 defaults it to multiscatter GGX).
"""
import os
import sys

import bpy
import numpy

numpy.bool = bool  # Debian's Blender 3.4 glTF importer still uses it

HERE = os.path.dirname(os.path.abspath(__file__))
SIZE = 128
ALBEDO = ["textured_box", "wrapped_box", "transform_box", "masked_leaf", "lit_spheres", "mapped_plane"]
DIRECT = ["lit_spheres", "mapped_plane"]
FRAMES = {"skinned_arm": [0, 5, 9], "morph_box": [0, 5, 9]}


def setup(name, samples):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.join(HERE, name + ".gltf"))
    scene = bpy.context.scene
    scene.camera = next(o for o in scene.objects if o.type == "CAMERA")
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.cycles.filter_width = 0.01
    scene.render.resolution_x = scene.render.resolution_y = SIZE
    scene.render.resolution_percentage = 100
    if scene.world is None:
        scene.world = bpy.data.worlds.new("black")
    scene.world.use_nodes = False
    scene.world.color = (0, 0, 0)
    for light in bpy.data.lights:
        if light.type == "SUN":
            light.angle = 0
        else:
            light.shadow_soft_size = 0
    for material in bpy.data.materials:
        if material.node_tree:
            for node in material.node_tree.nodes:
                if node.type == "BSDF_PRINCIPLED":
                    node.distribution = "GGX"
    scene.use_nodes = True
    scene.node_tree.nodes.clear()
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    return scene


def render_albedo(name, frame=None):
    scene = setup(name, 16)
    if frame is not None:
        scene.frame_set(frame)
    scene.view_layers[0].use_pass_diffuse_color = True
    tree = scene.node_tree
    rl = tree.nodes.new("CompositorNodeRLayers")
    out = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(rl.outputs["DiffCol"], out.inputs["Image"])
    suffix = ".albedo.exr" if frame is None else ".f%d.albedo.exr" % frame
    scene.render.filepath = os.path.join(HERE, name + suffix)
    bpy.ops.render.render(write_still=True)


def render_direct(name):
    scene = setup(name, 512)
    layer = scene.view_layers[0]
    layer.use_pass_diffuse_color = layer.use_pass_diffuse_direct = True
    layer.use_pass_glossy_color = layer.use_pass_glossy_direct = True
    tree = scene.node_tree
    rl = tree.nodes.new("CompositorNodeRLayers")

    def mix(kind, a, b):
        node = tree.nodes.new("CompositorNodeMixRGB")
        node.blend_type = kind
        node.use_clamp = False
        node.inputs["Fac"].default_value = 1.0
        tree.links.new(a, node.inputs[1])
        tree.links.new(b, node.inputs[2])
        return node.outputs["Image"]

    diffuse = mix("MULTIPLY", rl.outputs["DiffDir"], rl.outputs["DiffCol"])
    glossy = mix("MULTIPLY", rl.outputs["GlossDir"], rl.outputs["GlossCol"])
    out = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(mix("ADD", diffuse, glossy), out.inputs["Image"])
    scene.render.filepath = os.path.join(HERE, name + ".direct.exr")
    bpy.ops.render.render(write_still=True)


for name in ALBEDO:
    render_albedo(name)
for name in DIRECT:
    render_direct(name)
for name, frames in FRAMES.items():
    for frame in frames:
        render_albedo(name, frame)
sys.exit(0)
