"""The add-on's panels: holoray's settings in the Render properties, shown
when the render engine is holoray."""

import bpy


class _RenderPanel:
    """Where holoray's panels go: the Render properties, with holoray as the engine."""
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {"HOLORAY"}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES


class HOLORAY_PT_camera(_RenderPanel, bpy.types.Panel):
    bl_label = "holoray"

    def draw(self, context):
        s = context.scene.holoray
        layout = self.layout
        layout.use_property_split = True
        layout.prop(s, "camera")
        if s.camera == "INTEGRAL":
            col = layout.column(align=True)
            col.prop(s, "grid")
            col.prop(s, "lenses_x")
            if s.grid != "LENTICULAR":
                col.prop(s, "lenses_y")
            else:
                col.prop(s, "lenticular_rows")
            col.prop(s, "pixels_per_lens")
            layout.prop(s, "use_gap")
            layout.prop(s, "gap" if s.use_gap else "fov_lens")
            layout.prop(s, "mode")
            layout.label(text="The array stands at the camera's focus distance", icon="INFO")
            layout.operator("holoray.render_animation", icon="RENDER_ANIMATION")
        elif s.camera == "QUILT":
            col = layout.column(align=True)
            col.prop(s, "quilt_columns")
            col.prop(s, "quilt_rows")
            col.prop(s, "view_width")
            col.prop(s, "view_height")
            layout.prop(s, "view_cone")
        elif s.camera == "DISPLAY":
            layout.prop(s, "display_file")
        elif s.camera == "LOOKING_GLASS":
            layout.prop(s, "calibration_file")
        row = layout.row(align=True)
        row.operator("holoray.preview", text="Centre view").kind = "CENTRE"
        row.operator("holoray.preview", text="Every view").kind = "VIEWS"
        if s.camera == "DISPLAY":
            row.operator("holoray.preview", text="Eye").kind = "EYE"
        if s.camera in ("INTEGRAL", "QUILT"):
            layout.operator("holoray.export_web", icon="WORLD")


class HOLORAY_PT_tracing(_RenderPanel, bpy.types.Panel):
    bl_label = "Tracing"
    bl_parent_id = "HOLORAY_PT_camera"

    def draw(self, context):
        s = context.scene.holoray
        layout = self.layout
        layout.use_property_split = True
        layout.prop(s, "integrator")
        layout.prop(s, "samples")
        if s.integrator == "PATH":
            row = layout.row(align=True)
            row.prop(s, "seed")
            row.prop(s, "use_animated_seed", text="", icon="TIME")
        if s.camera == "QUILT" and s.integrator == "PATH" and s.device == "CPU":
            layout.prop(s, "share_views")
        layout.prop(s, "max_depth")
        layout.prop(s, "device")
        if s.device == "GPU":
            layout.prop(s, "gpu_device")
        layout.prop(s, "threads")
        layout.prop(s, "backend")
        col = layout.column(heading="Passes")
        col.prop(s, "aov_albedo")
        col.prop(s, "aov_depth")
        col.prop(s, "aov_normal")


classes = (HOLORAY_PT_camera, HOLORAY_PT_tracing)

# Blender's own panels that apply to any engine (output size, frame range, colour management).
_SHARED_PANELS = ("RENDER_PT_format", "RENDER_PT_frame_range", "RENDER_PT_output", "RENDER_PT_color_management",
                  "RENDER_PT_dimensions")


def register_panels():
    for name in _SHARED_PANELS:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.add("HOLORAY")


def unregister_panels():
    for name in _SHARED_PANELS:
        panel = getattr(bpy.types, name, None)
        if panel is not None and hasattr(panel, "COMPAT_ENGINES"):
            panel.COMPAT_ENGINES.discard("HOLORAY")
