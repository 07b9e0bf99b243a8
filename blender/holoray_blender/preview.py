"""Seeing the last render without a display: the operator holoray.preview
turns the last EIA (kept by the engine as last.exr in Blender's temporary
folder) into the centre sub-aperture view, the grid of every sub-aperture
view, or what an eye sees on the chosen display (`holoray subaperture`,
`holoray views`, `holoray simulate`), loaded as the image "holoray preview"
and shown in an image editor; holoray.export_web writes the last EIA or
quilt as a light-field page any browser opens (`holoray web`)."""

import json
import os
import subprocess

import bpy

from .properties import holoray_binary


# The last in-process render, (image, write_image), until a preview asks for
# its file: writing it after every render would cost what the module saves.
_unwritten = None


def last_render():
    """(path of the last EIA or panel image, its settings) or None."""
    global _unwritten
    path = os.path.join(bpy.app.tempdir, "holoray_last.exr")
    if _unwritten is not None:
        image, write = _unwritten
        write(path, image)
        _unwritten = None
    info = path + ".json"
    if not (os.path.isfile(path) and os.path.isfile(info)):
        return None
    with open(info) as f:
        return path, json.load(f)


def _keep_settings(path, s):
    with open(path + ".json", "w") as f:
        json.dump({"camera": s.camera, "grid": s.grid.lower(), "pixels_per_lens": s.pixels_per_lens,
                   "display_file": bpy.path.abspath(s.display_file) if s.display_file else "",
                   "quilt": f"{s.quilt_columns}x{s.quilt_rows}"}, f)


def keep_last(output, settings):
    """Called by the engine after a program render: keeps `output` and what it was made with."""
    global _unwritten
    _unwritten = None
    path = os.path.join(bpy.app.tempdir, "holoray_last.exr")
    os.replace(output, path)
    _keep_settings(path, settings)


def keep_last_image(image, write_image, settings):
    """Called by the engine after an in-process render: `image` (H, W, 3),
    written by write_image(path, image) when a preview first needs it."""
    global _unwritten
    path = os.path.join(bpy.app.tempdir, "holoray_last.exr")
    if os.path.exists(path):
        os.remove(path)
    _unwritten = (image, write_image)
    _keep_settings(path, settings)


def _last_and_binary(operator, context):
    """(the last render's path, its settings, the holoray program), or None
    once the operator has reported which is missing."""
    last = last_render()
    if last is None:
        operator.report({"ERROR"}, "holoray: nothing rendered yet: render with holoray (F12) first")
        return None
    binary = holoray_binary(context)
    if binary is None:
        operator.report({"ERROR"}, "holoray: the holoray program was not found")
        return None
    return last[0], last[1], binary


class HOLORAY_OT_preview(bpy.types.Operator):
    """Show the last holoray render as a viewer would see it, in the image editor"""

    bl_idname = "holoray.preview"
    bl_label = "Preview the last holoray render"

    kind: bpy.props.EnumProperty(
        name="Preview", default="CENTRE",
        items=[("CENTRE", "Centre view", "The centre sub-aperture view: the scene seen straight through the array"),
               ("VIEWS", "Every view", "Every sub-aperture view in a grid, view (u, v) at tile column u, row v"),
               ("EYE", "Eye on the display", "What an eye 600 mm in front of the display sees (display camera)")])

    def execute(self, context):
        found = _last_and_binary(self, context)
        if found is None:
            return {"CANCELLED"}
        path, info, binary = found
        out = os.path.join(bpy.app.tempdir, f"holoray_preview_{self.kind.lower()}.exr")
        p = str(info["pixels_per_lens"])
        if self.kind == "EYE":
            if info["camera"] != "DISPLAY":
                self.report({"ERROR"}, "holoray: the eye's view needs the Display camera (a display file)")
                return {"CANCELLED"}
            cmd = [binary, "simulate", path, "--display", info["display_file"], "-o", out]
        elif info["camera"] != "INTEGRAL":
            self.report({"ERROR"}, "holoray: sub-aperture views are made from a lens array's EIA (camera: Lens array)")
            return {"CANCELLED"}
        elif self.kind == "CENTRE":
            cmd = [binary, "subaperture", path, "--grid", info["grid"], "--pixels-per-lens", p, "-o", out]
        else:
            cmd = [binary, "views", path, "--grid", info["grid"], "--pixels-per-lens", p, "-o", out]
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode != 0:
            self.report({"ERROR"}, f"holoray: {run.stderr.strip()}")
            return {"CANCELLED"}
        old = bpy.data.images.get("holoray preview")
        if old is not None:
            bpy.data.images.remove(old)
        img = bpy.data.images.load(out, check_existing=False)
        img.name = "holoray preview"
        img.pack()  # the file is temporary
        for window in context.window_manager.windows:
            for area in window.screen.areas:
                if area.type == "IMAGE_EDITOR":
                    area.spaces[0].image = img
        self.report({"INFO"}, f"holoray: {img.size[0]}x{img.size[1]} preview in the image 'holoray preview'")
        return {"FINISHED"}


class HOLORAY_OT_export_web(bpy.types.Operator):
    """Write the last holoray render (a lens array's EIA or a quilt) as a light-field page any browser opens"""

    bl_idname = "holoray.export_web"
    bl_label = "Export web page"

    directory: bpy.props.StringProperty(name="Folder", subtype="DIR_PATH",
                                        description="Folder to write the page into (index.html, its script, the views)")

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        found = _last_and_binary(self, context)
        if found is None:
            return {"CANCELLED"}
        path, info, binary = found
        if not self.directory:
            self.report({"ERROR"}, "holoray: choose a folder for the page")
            return {"CANCELLED"}
        out = bpy.path.abspath(self.directory)
        name = bpy.path.display_name_from_filepath(bpy.data.filepath) or context.scene.name
        if info["camera"] == "INTEGRAL":
            cmd = [binary, "web", path, "--grid", info["grid"], "--pixels-per-lens", str(info["pixels_per_lens"])]
        elif info["camera"] == "QUILT":
            cmd = [binary, "web", path, "--quilt", info.get("quilt", "8x6")]
        else:
            self.report({"ERROR"}, "holoray: a web page shows a lens array's EIA or a quilt (camera: Lens array or Quilt)")
            return {"CANCELLED"}
        run = subprocess.run(cmd + ["--name", name, "-q", "-o", out], capture_output=True, text=True)
        if run.returncode != 0:
            self.report({"ERROR"}, f"holoray: {run.stderr.strip()}")
            return {"CANCELLED"}
        self.report({"INFO"}, f"holoray: page written in {out}: open it with `holoray web --serve {out}`")
        return {"FINISHED"}
