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
import threading

import bpy

from . import devices, export, job, placement
from .engine import HolorayError
from .properties import holoray_binary


def _v(v):
    return "[" + ", ".join(f"{x:.9g}" for x in placement.to_gltf(v)) + "]"


def shot_text(scene, camera_object, first, last, fps):
    """The shot file: the array's settings and its placement at every frame."""
    width_px, height_px = scene.render.resolution_x, scene.render.resolution_y
    a = job.spec(scene, scene.holoray, camera_object, width_px, height_px)  # the lens array, as F12 renders it
    lines = [f"frames = {last + 1}", f"fps = {fps:.9g}", "", "[array]", f'grid = "{a["grid"]}"',
             f'mode = "{a["mode"]}"', "lenses = [{}, {}]".format(*a["lenses"]), f"pixels_per_lens = {a['pixels_per_lens']}"]
    if a["rows"] is not None:
        lines.append(f"rows = {a['rows']}")
    lines.append(f"gap = {a['gap']:.9g}" if a["gap"] is not None else f"fov_lens = {a['fov_lens']:.9g}")
    lines += ["", "[camera]", 'interpolation = "linear"']
    current = scene.frame_current
    try:
        for f in range(first, last + 1):
            scene.frame_set(f)
            forward, up, right = placement.camera_axes(camera_object)
            d = placement.focus_distance(camera_object)
            width, height = placement.frame_size(camera_object, d, width_px / height_px)
            angle = math.degrees(2 * math.atan(width / 2 / d))
            # A shot places the array at `at`, facing `from`: a lens shift
            # moves both, so that the array stands where F12 puts it.
            cam, larger = camera_object.data, max(width, height)
            eye = camera_object.matrix_world.translation + right * (cam.shift_x * larger) + up * (cam.shift_y * larger)
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
            self._prepare(context)
            if bpy.app.background:  # no event loop: run to the end here
                self._run_blocking(context)
                self._finish(context)
                return {"FINISHED"}
        except (HolorayError, placement.PlacementError) as e:
            self.report({"ERROR"}, f"holoray: {e}")
            return {"CANCELLED"}
        except Exception as e:  # noqa: BLE001 - a report, never a traceback in the user's face
            self.report({"ERROR"}, f"holoray: {type(e).__name__}: {e}")
            return {"CANCELLED"}
        # In the interface: holoray runs while Blender stays responsive; the
        # progress bar follows its frames and Esc stops it between frames
        # (holoray animate's SIGTERM), leaving every finished frame for --resume.
        self._start()
        self._frame = None
        self._timer = context.window_manager.event_timer_add(0.2, window=context.window)
        context.window_manager.progress_begin(self._first, self._last)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        wm = context.window_manager
        if event.type == "ESC":
            self._proc.terminate()
            self._proc.wait()
            self._end(context)
            self.report({"WARNING"}, "holoray: stopped; the finished frames stay, and the next run resumes after them")
            return {"CANCELLED"}
        if event.type != "TIMER":
            return {"PASS_THROUGH"}
        if self._frame is not None:
            wm.progress_update(self._frame)
        if self._proc.poll() is None:
            return {"PASS_THROUGH"}
        self._reader.join()
        self._end(context)
        try:
            if self._proc.returncode != 0:
                raise HolorayError(self._err.strip() or f"holoray animate exited with status {self._proc.returncode}")
            self._finish(context)
        except Exception as e:  # noqa: BLE001
            self.report({"ERROR"}, f"holoray: {e}")
            return {"CANCELLED"}
        return {"FINISHED"}

    def _end(self, context):
        context.window_manager.event_timer_remove(self._timer)
        context.window_manager.progress_end()

    def _prepare(self, context):
        """Checks the scene, exports it, writes the shot: the command in self._cmd."""
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
        self._out_dir = os.path.dirname(bpy.path.abspath(scene.render.frame_path(frame=scene.frame_start)))
        work = os.path.join(self._out_dir, ".holoray")
        self._frames_dir = os.path.join(work, "frames")
        os.makedirs(self._frames_dir, exist_ok=True)
        self._first = 0 if self.video else scene.frame_start
        self._last = scene.frame_end
        fps = scene.render.fps / scene.render.fps_base
        export.export_gltf(work, scene, camera_object, animations=True)
        shot = os.path.join(work, "shot.toml")
        with open(shot, "w") as f:
            f.write(shot_text(scene, camera_object, self._first, self._last, fps))
        exr = scene.render.image_settings.file_format in ("OPEN_EXR", "OPEN_EXR_MULTILAYER")
        self._ext = "exr" if exr else "png"
        cmd = [binary, "animate", shot, "-o", self._frames_dir, "--resume", "--format", self._ext]
        if self._first > 0:
            cmd += ["--frames", f"{self._first}:{self._last}"]
        if self.video:
            cmd += ["--video", os.path.join(self._out_dir, "holoray.mkv")]
        if s.threads:
            cmd += ["--threads", str(s.threads)]
        if s.device != "CPU":
            cmd += ["--device", devices.device_argument(s)]
            if missing := devices.missing_gpu(s):
                self.report({"WARNING"}, f"holoray: {missing}")
        self._cmd = cmd

    def _start(self):
        """Starts holoray animate; a thread follows its frames and keeps its errors."""
        self._proc = subprocess.Popen(self._cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self._err = ""

        def read():
            for line in self._proc.stdout:
                m = re.match(r"frame\s+(\d+)", line)
                if m:
                    self._frame = int(m.group(1))
            self._err = self._proc.stderr.read()

        self._reader = threading.Thread(target=read, daemon=True)
        self._reader.start()

    def _run_blocking(self, context):
        self._frame = None
        self._start()
        self._proc.wait()
        self._reader.join()
        if self._proc.returncode != 0:
            raise HolorayError(self._err.strip() or f"holoray animate exited with status {self._proc.returncode}")

    def _finish(self, context):
        """Copies holoray's frames to Blender's output path."""
        scene = context.scene
        digits = max(4, len(str(self._last)))
        for f in range(scene.frame_start, self._last + 1):
            src = os.path.join(self._frames_dir, f"frame_{f:0{digits}d}.{self._ext}")
            dst = os.path.splitext(bpy.path.abspath(scene.render.frame_path(frame=f)))[0] + "." + self._ext
            shutil.copyfile(src, dst)
        self.report({"INFO"}, f"holoray: {self._last - scene.frame_start + 1} frames in {self._out_dir}")
