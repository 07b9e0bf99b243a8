"""holoray for Blender: the open scene as an elemental image array (EIA), a
pinhole view, a Looking Glass quilt or a display's panel image, rendered by
holoray (docs/guide/blender.md).

Registers the render engine HOLORAY (F12, `blender -b f.blend -E HOLORAY -f 1`),
the operators holoray.render_animation (a shot with keyframe reuse) and
holoray.preview (the last render as a viewer sees it), holoray.export_web (the
last EIA or quilt as a light-field page any browser opens),
its settings `scene.holoray` in the Render properties, and the add-on's
preferences (the holoray binary). Blender's own glTF exporter hands the scene
over; holoray renders it (its Python module in Blender's process, else the
program); the result comes back as the render result and its passes.
"""

bl_info = {
    "name": "holoray",
    "author": "holoray maintainers",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Properties > Render > Render Engine > holoray",
    "description": "Integral images (elemental image arrays), quilts and display panel images, rendered by holoray",
    "doc_url": "https://example.org/holoray/docs/guide/blender.md",
    "category": "Render",
}

if "bpy" in locals():  # reloaded (F8): take the modules' new code
    import importlib

    importlib.reload(devices)  # noqa: F821
    importlib.reload(properties)  # noqa: F821
    importlib.reload(job)  # noqa: F821
    importlib.reload(inprocess)  # noqa: F821
    importlib.reload(engine)  # noqa: F821
    importlib.reload(ui)  # noqa: F821
    importlib.reload(animation)  # noqa: F821
    importlib.reload(preview)  # noqa: F821

import bpy

from . import animation, devices, engine, inprocess, job, preview, properties, ui

_classes = (properties.HolorayPreferences, properties.HoloraySettings, engine.HolorayRenderEngine,
            animation.HOLORAY_OT_render_animation, preview.HOLORAY_OT_preview,
            preview.HOLORAY_OT_export_web) + ui.classes


def register():
    for c in _classes:
        bpy.utils.register_class(c)
    bpy.types.Scene.holoray = bpy.props.PointerProperty(type=properties.HoloraySettings)
    ui.register_panels()


def unregister():
    inprocess.release_gpu_devices()
    ui.unregister_panels()
    del bpy.types.Scene.holoray
    for c in reversed(_classes):
        bpy.utils.unregister_class(c)
