"""The scene as Blender sees it at the current frame (modifiers applied,
instances, what renders), written by Blender's own glTF exporter
(Principled BSDF as glTF PBR, image textures, lights as
KHR_lights_punctual), and a list of what does not survive the trip."""

import contextlib
import os
import sys

import bpy

from . import lighting

# Shader nodes the glTF exporter turns into glTF materials.
_EXPORTED_SHADERS = {"BSDF_PRINCIPLED", "EMISSION", "BSDF_DIFFUSE", "BSDF_GLOSSY", "MIX_SHADER", "ADD_SHADER"}
# Texture nodes that are images; every other texture node is procedural.
_IMAGE_TEXTURES = {"TEX_IMAGE", "TEX_ENVIRONMENT"}


def _renders(obj):
    return not obj.hide_render and obj.visible_get()


def not_exported(scene, path_tracing=False):
    """What holoray will not see, one sentence each: volumes, procedural
    textures, shaders glTF has no model for; without path tracing, area
    lights and the World; with it, what of the World it cannot read."""
    out, seen = [], set()
    for obj in scene.objects:
        if not _renders(obj):
            continue
        if obj.type == "LIGHT" and obj.data.type == "AREA" and not path_tracing:
            out.append(f"area light '{obj.name}': lights path tracing only (Integrator: Path tracing): left out")
        if obj.type == "VOLUME":
            out.append(f"volume '{obj.name}': glTF has no volumes: left out")
        for slot in getattr(obj, "material_slots", []):
            mat = slot.material
            if mat is None or mat.name in seen or not mat.use_nodes:
                continue
            seen.add(mat.name)
            nodes = mat.node_tree.nodes
            for node in nodes:
                if node.type.startswith("TEX_") and node.type not in _IMAGE_TEXTURES and node.outputs and any(
                        o.is_linked for o in node.outputs):
                    out.append(f"material '{mat.name}': procedural texture '{node.name}' ({node.bl_label}) is not "
                               "exported: its input's default shows instead (bake it to an image)")
            for node in nodes:
                if node.type != "OUTPUT_MATERIAL":
                    continue
                surface, volume = node.inputs["Surface"], node.inputs["Volume"]
                if volume.is_linked:
                    out.append(f"material '{mat.name}': its volume is not exported")
                if surface.is_linked and surface.links[0].from_node.type not in _EXPORTED_SHADERS:
                    shader = surface.links[0].from_node
                    out.append(f"material '{mat.name}': shader '{shader.name}' ({shader.bl_label}) has no glTF "
                               "model: exported as a default material")
    if path_tracing:
        return out + lighting.world(scene)[1]
    world = scene.world
    if world is not None and world.use_nodes:
        bg = next((n for n in world.node_tree.nodes if n.type == "BACKGROUND"), None)
        if bg is not None and (bg.inputs["Color"].is_linked or any(c > 0 for c in bg.inputs["Color"].default_value[:3])) \
                and bg.inputs["Strength"].default_value > 0:
            out.append("the world lights path tracing only (Integrator: Path tracing): holoray's background is black")
    return out


def export_gltf(directory, scene, camera_object, cameras=False, animations=False, lights=True):
    """Writes the scene into `directory` (scene.gltf, its .bin and images) and
    returns the .gltf's path. With `cameras`, the active camera is the only
    one written (holoray takes the file's first camera as its viewpoint)."""
    path = os.path.join(directory, "scene.gltf")
    hidden = []
    if cameras:  # the other cameras out of the way, for the exporter's use_renderable
        for obj in scene.objects:
            if obj.type == "CAMERA" and obj != camera_object and not obj.hide_render:
                obj.hide_render = True
                hidden.append(obj)
    try:
        # A render started from the command line (-f) runs without a view
        # layer or a window in its context; the exporter reads both.
        # The exporter also switches the window's scene while it gathers.
        layer = scene.view_layers[0]
        override = {"scene": scene, "view_layer": layer, "active_object": layer.objects.active,
                    "object": layer.objects.active, "selected_objects": [o for o in layer.objects if o.select_get()]}
        windows = bpy.context.window_manager.windows
        if bpy.context.window is None and len(windows):
            override["window"] = windows[0]
        with bpy.context.temp_override(**override), _bytecode_cache():
            result = _export(path, cameras, animations, lights)
    finally:
        for obj in hidden:
            obj.hide_render = False
    if "FINISHED" not in result or not os.path.isfile(path):
        raise RuntimeError(f"Blender's glTF exporter did not write {path}")
    return path


def _export(path, cameras, animations, lights):
    return bpy.ops.export_scene.gltf(
            filepath=path, export_format="GLTF_SEPARATE", check_existing=False, use_renderable=True,
            export_current_frame=True,
            use_active_scene=True, export_apply=True, export_lights=lights, export_cameras=cameras,
            export_animations=animations, export_yup=True, export_extras=False)


def _cache_dir():
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "holoray", "blender-bytecode")


@contextlib.contextmanager
def _bytecode_cache():
    """Blender runs with sys.dont_write_bytecode, so every Blender process
    compiled the glTF exporter's modules from source on its first export:
    55 ms of the first render's 73 ms export (bench/blender_results.md).
    While the exporter runs, Python writes and reads their bytecode under
    the user's cache folder (sys.pycache_prefix), never beside Blender's
    own files; Python checks each file against its source's mtime, so an
    upgraded Blender recompiles. An unwritable folder only means no cache."""
    saved = sys.dont_write_bytecode, sys.pycache_prefix
    sys.dont_write_bytecode, sys.pycache_prefix = False, _cache_dir()
    try:
        yield
    finally:
        sys.dont_write_bytecode, sys.pycache_prefix = saved
