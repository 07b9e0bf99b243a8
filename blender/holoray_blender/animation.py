"""The operator holoray.render_animation: the scene's frame range as a shot
with keyframe reuse. The animated scene is exported once (Blender's glTF
exporter, node animation baked), the camera's placement written per frame
into a shot file (docs/shot-format.md), `holoray animate` renders it into
OUTPUT/.holoray/frames (`--resume`: a stopped run goes on where it stopped),
and each frame is copied to Blender's output path. Also runnable headless:
`blender -b f.blend --addons holoray_blender --python-expr
"import bpy; bpy.ops.holoray.render_animation()"`."""

import math
import os
import re
import shutil
import subprocess

import bpy

from . import export, placement
from .engine import HolorayError
from .properties import holoray_binary


def _v(v):
    return "[" + ", ".join(f"{x:.9g}" for x in placement.to_gltf(v)) + "]"


def shot_text(scene, camera_object, first, last, fps):
    """The shot file: the array's settings and its placement at every frame."""
    s = scene.holoray
    lenses_y = s.lenses_y if s.grid != "LENTICULAR" else 1
    lines = [f"frames = {last + 1}", f"fps = {fps:.9g}", "", "[array]", f'grid = "{s.grid.lower()}"',
             f'mode = "{s.mode.lower()}"', f"lenses = [{s.lenses_x}, {lenses_y}]", f"pixels_per_lens = {s.pixels_per_lens}"]
    if s.grid == "LENTICULAR":
        lines.append(f"rows = {s.lenticular_rows}")
    lines.append(f"gap = {s.gap:.9g}" if s.use_gap else f"fov_lens = {s.fov_lens:.9g}")
    lines += ["", "[camera]", 'interpolation = "linear"']
    width_px, height_px = scene.render.resolution_x, scene.render.resolution_y
    current = scene.frame_current
    try:
        for f in range(first, last + 1):
            scene.frame_set(f)
            m = camera_object.matrix_world
            forward = (m.to_3x3().normalized() @ placement.Vector((0, 0, -1))).normalized()
            up = (m.to_3x3().normalized() @ placement.Vector((0, 1, 0))).normalized()
            d = placement.focus_distance(camera_object)
            width, _ = placement.frame_size(camera_object, d, width_px / height_px)
            angle = math.degrees(2 * math.atan(width / 2 / d))
            eye = m.translation
            lines += ["[[camera.key]]", f"frame = {f}", f"from = {_v(eye)}", f"at = {_v(eye + forward * d)}",
                      f"up = {_v(up)}", f"angle = {angle:.9g}"]
    finally:
        scene.frame_set(current)
    lines += ["", "[[object]]", 'scene = "scene.gltf"', ""]
    return "\n".join(lines)


class HOLORAY_OT_render_animation(bpy.types.Operator):
    """Render the frame range through holoray with keyframe reuse, into the output path"""

    bl_idname = "holoray.render_animation"
    bl_label = "Render Animation with holoray"

    video: bpy.props.BoolProperty(name="Video", default=False,
                                  description="Also write OUTPUT/holoray.mkv (FFV1, lossless); renders from frame 0")

    def execute(self, context):
        try:
            self._run(context)
        except (HolorayError, placement.PlacementError) as e:
            self.report({"ERROR"}, f"holoray: {e}")
            return {"CANCELLED"}
        except Exception as e:  # noqa: BLE001 - a report, never a traceback in the user's face
            self.report({"ERROR"}, f"holoray: {type(e).__name__}: {e}")
            return {"CANCELLED"}
        return {"FINISHED"}

    def _run(self, context):
        scene = context.scene
        s = scene.holoray
        if s.camera != "INTEGRAL":
            raise HolorayError("animations are rendered through the lens array (camera: Lens array)")
        camera_object = scene.camera
        if camera_object is None:
            raise HolorayError("the scene has no active camera: holoray places its lens array by it")
        binary = holoray_binary(context)
        if binary is None:
            raise HolorayError("the holoray program was not found: set its path in the add-on's preferences or put it on PATH")
        for line in export.not_exported(scene):
            self.report({"WARNING"}, f"holoray: {line}")
        out_dir = os.path.dirname(bpy.path.abspath(scene.render.frame_path(frame=scene.frame_start)))
        work = os.path.join(out_dir, ".holoray")
        frames_dir = os.path.join(work, "frames")
        os.makedirs(frames_dir, exist_ok=True)
        first = 0 if self.video else scene.frame_start
        last = scene.frame_end
        fps = scene.render.fps / scene.render.fps_base
        export.export_gltf(work, scene, camera_object, animations=True)
        shot = os.path.join(work, "shot.toml")
        with open(shot, "w") as f:
            f.write(shot_text(scene, camera_object, first, last, fps))
        exr = scene.render.image_settings.file_format in ("OPEN_EXR", "OPEN_EXR_MULTILAYER")
        cmd = [binary, "animate", shot, "-o", frames_dir, "--resume", "--format", "exr" if exr else "png"]
        if first > 0:
            cmd += ["--frames", f"{first}:{last}"]
        if self.video:
            cmd += ["--video", os.path.join(out_dir, "holoray.mkv")]
        if s.threads:
            cmd += ["--threads", str(s.threads)]
        wm = context.window_manager
        wm.progress_begin(first, last)
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        try:
            for line in proc.stdout:
                m = re.match(r"frame\s+(\d+)", line)
                if m:
                    wm.progress_update(int(m.group(1)))
            err = proc.stderr.read()
            proc.wait()
        finally:
            if proc.poll() is None:
                proc.terminate()
                proc.wait()
            wm.progress_end()
        if proc.returncode != 0:
            raise HolorayError(err.strip() or f"holoray animate exited with status {proc.returncode}")
        ext = "exr" if exr else "png"
        digits = max(4, len(str(last)))
        for f in range(scene.frame_start, last + 1):
            src = os.path.join(frames_dir, f"frame_{f:0{digits}d}.{ext}")
            dst = os.path.splitext(bpy.path.abspath(scene.render.frame_path(frame=f)))[0] + "." + ext
            shutil.copyfile(src, dst)
        self.report({"INFO"}, f"holoray: {last - scene.frame_start + 1} frames in {out_dir}")
