"""The render engine HOLORAY: F12, Ctrl-F12 and `blender -b f.blend -E HOLORAY
-f 1` render the scene through holoray. The scene is exported with Blender's
glTF exporter into a temporary folder, `holoray render` traces it (its
`progress` lines drive Blender's progress bar; Esc ends the process), and its
EXR files come back as the render result: colour into Combined, the AOVs
into the passes Depth (holoray's line parameter t), Normal and DiffCol
(albedo). Anything that goes wrong is a Blender error report."""

import glob
import os
import shutil
import subprocess
import tempfile
import threading
import time

import bpy
import numpy as np

from . import export, placement, preview
from .properties import holoray_binary, image_size


class HolorayError(Exception):
    """A reason the render cannot be made, for the error report."""


def _fmt(v):
    return ",".join(f"{x:.9g}" for x in v)


def command(binary, scene, settings, gltf, output, camera_object, width, height):
    """The `holoray render` command line for these settings."""
    cmd = [binary, "render", gltf, "-o", output, "-q", "--progress"]
    s = settings
    if s.camera == "INTEGRAL":
        p = s.pixels_per_lens
        lenses_y = s.lenses_y if s.grid != "LENTICULAR" else 1
        place = placement.array_placement(camera_object, width / height, s.mode == "PSEUDOSCOPIC")
        cmd += ["--grid", s.grid.lower(), "--lenses", f"{s.lenses_x}x{lenses_y}", "--pixels-per-lens", str(p),
                "--mode", s.mode.lower(),
                "--origin", _fmt(placement.to_gltf(place.origin)), "--normal", _fmt(placement.to_gltf(place.normal)),
                "--up", _fmt(placement.to_gltf(place.up)), "--pitch", f"{place.width / s.lenses_x:.9g}"]
        if s.grid == "LENTICULAR":
            cmd += ["--rows", str(s.lenticular_rows)]
        cmd += ["--gap", f"{s.gap:.9g}"] if s.use_gap else ["--fov-lens", f"{s.fov_lens:.9g}"]
    elif s.camera == "PINHOLE":
        cam = camera_object.data
        cmd += ["--camera", "pinhole", "--resolution", f"{width}x{height}",
                "--shift", f"{cam.shift_x:.9g},{cam.shift_y:.9g}"]
    elif s.camera == "QUILT":
        cmd += ["--quilt", f"{s.quilt_columns}x{s.quilt_rows}", "--resolution", f"{s.view_width}x{s.view_height}",
                "--view-cone", f"{s.view_cone:.9g}",
                "--focus-distance", f"{placement.focus_distance(camera_object):.9g}"]
    elif s.camera == "DISPLAY":
        cmd += ["--display", bpy.path.abspath(s.display_file)]
    elif s.camera == "LOOKING_GLASS":
        cmd += ["--looking-glass", bpy.path.abspath(s.calibration_file),
                "--focus-distance", f"{placement.focus_distance(camera_object):.9g}"]
    if s.max_depth:
        cmd += ["--max-depth", str(s.max_depth)]
    if s.threads:
        cmd += ["--threads", str(s.threads)]
    aovs = [name for name, on in (("albedo", s.aov_albedo), ("depth", s.aov_depth), ("normal", s.aov_normal)) if on]
    if aovs and s.camera not in ("DISPLAY", "LOOKING_GLASS"):
        cmd += ["--aov", ",".join(aovs)]
    return cmd, aovs


def read_exr(path, width, height):
    """An EXR holoray wrote, as Blender's bottom-up float rows: (height * width, channels)."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        if tuple(img.size) != (width, height):
            raise HolorayError(f"holoray wrote a {img.size[0]}x{img.size[1]} image, the render is {width}x{height}")
        px = np.empty(width * height * 4, dtype=np.float32)
        img.pixels.foreach_get(px)
        return px.reshape(height * width, 4)
    finally:
        bpy.data.images.remove(img)


class HolorayRenderEngine(bpy.types.RenderEngine):
    bl_idname = "HOLORAY"
    bl_label = "holoray"
    bl_use_preview = False
    bl_use_postprocess = True

    _PASSES = (("albedo", "DiffCol", 3, "RGB", "COLOR"), ("depth", "Depth", 1, "Z", "VALUE"),
               ("normal", "Normal", 3, "XYZ", "VECTOR"))

    def update_render_passes(self, scene=None, renderlayer=None):
        self.register_pass(scene, renderlayer, "Combined", 4, "RGBA", "COLOR")
        s = scene.holoray
        for aov, name, channels, chan_id, kind in self._PASSES:
            if getattr(s, f"aov_{aov}"):
                self.register_pass(scene, renderlayer, name, channels, chan_id, kind)

    def render(self, depsgraph):
        scene = depsgraph.scene
        workdir = tempfile.mkdtemp(prefix="holoray-blender-")
        try:
            self._render(scene, workdir)
        except (HolorayError, placement.PlacementError) as e:
            self.report({"ERROR"}, f"holoray: {e}")
        except Exception as e:  # noqa: BLE001 - a report, never a traceback in the user's face
            self.report({"ERROR"}, f"holoray: {type(e).__name__}: {e}")
        finally:
            shutil.rmtree(workdir, ignore_errors=True)

    def _render(self, scene, workdir):
        s = scene.holoray
        r = scene.render
        width, height = int(r.resolution_x * r.resolution_percentage / 100), int(r.resolution_y * r.resolution_percentage / 100)
        camera_object = scene.camera
        if camera_object is None:
            raise HolorayError("the scene has no active camera: holoray places its lens array (or view) by it")
        expected = image_size(s)
        if expected is not None and tuple(expected) != (width, height):
            raise HolorayError(f"the render is {width}x{height} px, the {s.camera.lower()} camera makes {expected[0]}x"
                               f"{expected[1]}: set the resolution to it at 100 % (changing a holoray setting does)")
        if not any(o.type in ("MESH", "CURVE", "SURFACE", "META", "FONT") and not o.hide_render for o in scene.objects):
            raise HolorayError("the scene has nothing to render: no mesh, curve or text object renders")
        binary = holoray_binary(bpy.context)
        if binary is None:
            raise HolorayError("the holoray program was not found: set its path in the add-on's preferences "
                               "(Edit > Preferences > Add-ons > holoray) or put it on PATH")
        for line in export.not_exported(scene):
            self.report({"WARNING"}, f"holoray: {line}")
        self.update_stats("holoray", "exporting the scene (glTF)")
        t0 = time.perf_counter()
        gltf = export.export_gltf(workdir, scene, camera_object, cameras=s.camera != "INTEGRAL")
        output = os.path.join(workdir, "out.exr")
        cmd, aovs = command(binary, scene, s, gltf, output, camera_object, width, height)
        self.update_stats("holoray", "tracing")
        t1 = time.perf_counter()
        self._run(cmd)
        if self.test_break():
            return
        t2 = time.perf_counter()
        result = self.begin_result(0, 0, width, height)
        layer = result.layers[0]
        if s.camera == "QUILT":  # holoray names a quilt by its layout: out_qsCxRaA.exr
            output = next(iter(glob.glob(os.path.join(workdir, "out_qs*.exr"))), output)
        # Blender's own reader straight into the layer (EXR to Combined, in C).
        layer.load_from_file(output)
        for aov, name, channels, _, _ in self._PASSES:
            if aov in aovs and name in layer.passes:
                px = read_exr(f"{os.path.splitext(output)[0]}.{aov}.exr", width, height)
                layer.passes[name].rect = np.ascontiguousarray(px[:, :channels])
        self.end_result(result)
        t3 = time.perf_counter()
        preview.keep_last(output, s)  # for holoray.preview
        # What the add-on itself costs beside holoray's run (bench/run_blender_bench.sh reads it).
        print(f"holoray: {width}x{height}: export {t1 - t0:.3f} s, holoray {t2 - t1:.3f} s, "
              f"result {t3 - t2:.3f} s", flush=True)

    def _run(self, cmd):
        """Runs holoray, following its progress; Esc (test_break) ends it."""
        try:
            proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        except OSError as e:
            raise HolorayError(f"cannot run {cmd[0]}: {e.strerror}") from None
        errors = []

        def read():  # stderr: progress lines, else error text
            for line in proc.stderr:
                if line.startswith("progress "):
                    try:
                        self.update_progress(float(line.split()[1]))
                    except ValueError:
                        pass
                else:
                    errors.append(line.rstrip())

        reader = threading.Thread(target=read, daemon=True)
        reader.start()
        while proc.poll() is None:
            if self.test_break():
                proc.terminate()
                try:
                    proc.wait(timeout=5)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
                break
            try:
                proc.wait(timeout=0.1)
            except subprocess.TimeoutExpired:
                pass
        reader.join(timeout=5)
        if proc.returncode != 0 and not self.test_break():
            raise HolorayError("\n".join(errors) or f"{cmd[0]} exited with status {proc.returncode}")
