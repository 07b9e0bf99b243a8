"""The add-on's settings: `scene.holoray` (what to render) and the
preferences (where holoray is). The render resolution follows the camera:
lenses x pixels per lens for an EIA, the quilt's views, the panel's size."""

import json
import math
import os
import shutil
import tomllib

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import devices

ADDON = __package__


def holoray_binary(context):
    """The holoray CLI: the preferences' path, else `holoray` on PATH; None if neither."""
    prefs = context.preferences.addons.get(ADDON)
    path = prefs.preferences.binary if prefs else ""
    if path:
        return path if os.path.isfile(path) and os.access(path, os.X_OK) else None
    return shutil.which("holoray")


def _gpu_choices(self, context):
    return devices.choices(holoray_binary(context or bpy.context))


def panel_size(settings):
    """A display file's or calibration's panel size (width, height), or None."""
    try:
        if settings.camera == "DISPLAY" and settings.display_file:
            with open(bpy.path.abspath(settings.display_file), "rb") as f:
                panel = tomllib.load(f)["panel"]
            return tuple(int(v) for v in panel["resolution"])
        if settings.camera == "LOOKING_GLASS" and settings.calibration_file:
            with open(bpy.path.abspath(settings.calibration_file)) as f:
                cal = json.load(f)
            value = lambda k: int(cal[k]["value"] if isinstance(cal[k], dict) else cal[k])  # noqa: E731
            return value("screenW"), value("screenH")
    except (OSError, KeyError, ValueError, TypeError, tomllib.TOMLDecodeError):
        return None
    return None


def image_size(settings):
    """The image holoray will write for these settings, (width, height), or None when it comes from the scene."""
    if settings.camera == "INTEGRAL":
        p = settings.pixels_per_lens
        if settings.grid == "LENTICULAR":
            return settings.lenses_x * p, settings.lenticular_rows
        if settings.grid == "HEX":  # rows of hexagons sqrt(3)/2 apart (docs/camera-model.md), rounded as holoray does
            return settings.lenses_x * p, math.floor(settings.lenses_y * p * math.sqrt(3) / 2 + 0.5)
        return settings.lenses_x * p, settings.lenses_y * p
    if settings.camera == "QUILT":
        return settings.quilt_columns * settings.view_width, settings.quilt_rows * settings.view_height
    if settings.camera in ("DISPLAY", "LOOKING_GLASS"):
        return panel_size(settings)
    return None  # PINHOLE: the scene's own resolution


def follow_camera(settings, context):
    """Sets the render resolution to the image holoray writes (100 %)."""
    size = image_size(settings)
    if size is None:
        return
    r = context.scene.render
    r.resolution_x, r.resolution_y = size
    r.resolution_percentage = 100


class HolorayPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON
    binary: StringProperty(name="holoray binary", subtype="FILE_PATH",
                           description="The holoray command line program; empty: `holoray` on PATH")

    def draw(self, context):
        self.layout.prop(self, "binary")
        found = holoray_binary(context)
        self.layout.label(text=f"Using {found}" if found else "holoray not found: set its path or install it",
                          icon="CHECKMARK" if found else "ERROR")


class HoloraySettings(bpy.types.PropertyGroup):
    camera: EnumProperty(
        name="Camera", update=follow_camera, default="INTEGRAL",
        items=[("INTEGRAL", "Lens array (EIA)", "An elemental image array for a lens array at the camera's focus distance"),
               ("PINHOLE", "Pinhole", "The active camera's own view"),
               ("QUILT", "Quilt", "A Looking Glass quilt of sheared views"),
               ("DISPLAY", "Display", "A physical panel's native image, from its display file"),
               ("LOOKING_GLASS", "Looking Glass", "A Looking Glass's native image, from its calibration")])
    lenses_x: IntProperty(name="Lenses X", default=64, min=1, soft_max=1024, update=follow_camera)
    lenses_y: IntProperty(name="Lenses Y", default=64, min=1, soft_max=1024, update=follow_camera)
    pixels_per_lens: IntProperty(name="Pixels per lens", default=8, min=1, soft_max=64, update=follow_camera)
    lenticular_rows: IntProperty(name="Rows", default=512, min=1, description="Image rows of a lenticular sheet",
                                 update=follow_camera)
    grid: EnumProperty(name="Grid", default="SQUARE", update=follow_camera,
                       items=[("SQUARE", "Square", ""), ("HEX", "Hexagonal", ""), ("LENTICULAR", "Lenticular", "")])
    use_gap: BoolProperty(name="Gap instead of field of view", default=False)
    fov_lens: FloatProperty(name="Lens field of view", default=20.0, min=0.1, max=179.0, description="Degrees")
    gap: FloatProperty(name="Gap", default=0.1, min=1e-6, description="Lens plane to pixels, scene units")
    mode: EnumProperty(name="Mode", default="ORTHOSCOPIC",
                       items=[("ORTHOSCOPIC", "Orthoscopic", "Display-ready"),
                              ("PSEUDOSCOPIC", "Pseudoscopic", "A direct pickup")])
    quilt_columns: IntProperty(name="Columns", default=8, min=1, max=64, update=follow_camera)
    quilt_rows: IntProperty(name="Rows", default=6, min=1, max=64, update=follow_camera)
    view_width: IntProperty(name="View width", default=420, min=1, update=follow_camera)
    view_height: IntProperty(name="View height", default=560, min=1, update=follow_camera)
    view_cone: FloatProperty(name="View cone", default=40.0, min=0.0, max=180.0, description="Degrees")
    display_file: StringProperty(name="Display file", subtype="FILE_PATH", update=follow_camera)
    calibration_file: StringProperty(name="Calibration", subtype="FILE_PATH", update=follow_camera)
    integrator: EnumProperty(
        name="Integrator", default="PATH",
        items=[("PATH", "Path tracing", "Light as Cycles renders it: the World, area lights, soft shadows, light "
                "between surfaces; noise falls with the samples (CPU or GPU)"),
               ("WHITTED", "Whitted", "The paper's ray tracing: point, spot and sun lights, hard shadows, mirrors; "
                "exact and fast, no World light")])
    samples: IntProperty(name="Samples", default=64, min=1, soft_max=4096,
                         description="Samples per pixel (path tracing; Whitted: antialiasing)")
    share_views: IntProperty(
        name="Shared views", default=0, min=0, max=16,
        description="A quilt path traced on the CPU: each view also takes the samples of this many views on each side "
                    "that see the same surface; less noise where light, not edges, makes it (docs/guide/light.md). 0: none")
    seed: IntProperty(name="Seed", default=0, min=0,
                      description="Path tracing: the samples' seed; renders with different seeds have independent noise")
    use_animated_seed: BoolProperty(name="Animated seed", default=False,
                                    description="Path tracing: the frame's number added to the seed, so that each frame's "
                                                "noise is its own")
    max_depth: IntProperty(name="Ray depth", default=0, min=0, max=16,
                           description="0: 5, holoray's default (path tracing: Cycles' bounces plus 1)")
    threads: IntProperty(name="Threads", default=0, min=0, description="0: all cores")
    device: EnumProperty(
        name="Device", default="CPU",
        items=[("CPU", "CPU", "Embree on the CPU's cores"),
               ("GPU", "GPU", "The GPU path (Vulkan); every frame traced in full")])
    gpu_device: EnumProperty(name="GPU", default=0, items=_gpu_choices,
                             description="The Vulkan device the GPU path takes: the first GPU, or one by name")
    backend: EnumProperty(
        name="Run holoray", default="AUTO",
        items=[("AUTO", "Automatic", "holoray's Python module inside Blender where it loads, else the holoray program"),
               ("MODULE", "Python module", "holoray's Python module inside Blender: no files written or read back"),
               ("PROGRAM", "Program", "The holoray program (the add-on's preferences, else PATH), through EXR files")])
    aov_albedo: BoolProperty(name="Albedo", default=False)
    aov_depth: BoolProperty(name="Depth", default=False)
    aov_normal: BoolProperty(name="Normal", default=False)
