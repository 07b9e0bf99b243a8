"""The render engine HOLORAY: F12, Ctrl-F12 and `blender -b f.blend -E HOLORAY
-f 1` render the scene through holoray. The scene is exported with Blender's
glTF exporter into a temporary folder and traced one of two ways
(`scene.holoray.backend`): by holoray's Python module in Blender's own
process, its arrays going straight into the render result (where the module
loads: the default), or by `holoray render`, whose `progress` lines drive the
progress bar and whose EXR files Blender reads back. Colour goes into
Combined, the AOVs into the passes Depth (holoray's line parameter t),
Normal and DiffCol (albedo). Esc stops either (the process ends, or the
module's render stops after its current tile). Anything that goes wrong is a
Blender error report."""

import glob
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

import bpy
import numpy as np

from . import devices, export, inprocess, job, lighting, placement, preview
from .properties import holoray_binary, image_size


class HolorayError(Exception):
    """A reason the render cannot be made, for the error report."""


class _Stopped(Exception):
    """Esc during an in-process render: raised from its progress callback."""


def command(binary, scene, settings, gltf, output, camera_object, width, height, lights_file=None):
    """The `holoray render` command line for these settings, and the AOVs it writes."""
    j = job.spec(scene, settings, camera_object, width, height, lights_file)
    # Uncompressed: the files are read once and deleted, and ZIP took holoray
    # as long as the trace (bench/blender_results.md).
    cmd = [binary, "render", gltf, "-o", output, "-q", "--progress", "--exr-compression", "none"] + job.cli_args(j)
    return cmd, j["aovs"]


def _fill(render_pass, px):
    """A pass's pixels from (pixels, channels) values, Blender's rows bottom up.
    foreach_set takes the buffer whole: 2 ms for 1024x1024 RGBA, where
    assigning `rect` converts value by value (336 ms). Blender 4.1 and later
    take the values flat; before, one row per pixel."""
    px = np.ascontiguousarray(px, dtype=np.float32)
    render_pass.rect.foreach_set(px.reshape(-1) if bpy.app.version >= (4, 1, 0) else px)


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
        module = inprocess.find_module(binary) if s.backend != "PROGRAM" else None
        if s.backend == "MODULE" and module is None:
            raise HolorayError("holoray's Python module does not load in Blender's Python "
                               f"{sys.version_info.major}.{sys.version_info.minor}: install holoray's package, "
                               "or choose the program as the way to run holoray")
        if module is None and binary is None:
            raise HolorayError("the holoray program was not found: set its path in the add-on's preferences "
                               "(Edit > Preferences > Add-ons > holoray) or put it on PATH")
        path_tracing = job.path_tracing(s)
        for line in export.not_exported(scene, path_tracing):
            self.report({"WARNING"}, f"holoray: {line}")
        if missing := devices.missing_gpu(s):
            self.report({"WARNING"}, f"holoray: {missing}")
        self.update_stats("holoray", "exporting the scene (glTF)")
        t0 = time.perf_counter()
        # Path tracing takes the lights from a lights file (their radii, sun
        # angles and area lights, which glTF cannot carry), not the glTF.
        gltf = export.export_gltf(workdir, scene, camera_object, cameras=s.camera != "INTEGRAL", lights=not path_tracing)
        self._lights_file = None
        if path_tracing:
            self._lights_file = os.path.join(workdir, "lights.toml")
            lighting.write_lights(scene, self._lights_file)
        self.update_stats("holoray", "tracing")
        t1 = time.perf_counter()
        if module is not None:
            done = self._render_in_process(module, gltf, scene, camera_object, width, height, t0, t1)
        else:
            done = self._render_program(binary, gltf, workdir, scene, camera_object, width, height, t0, t1)
        if done:  # what the add-on itself costs beside holoray's run (bench/run_blender_bench.sh reads it)
            (t0, t1, t2, t3), way = done
            print(f"holoray: {width}x{height}: export {t1 - t0:.3f} s, holoray {t2 - t1:.3f} s, "
                  f"result {t3 - t2:.3f} s ({way})", flush=True)

    def _render_program(self, binary, gltf, workdir, scene, camera_object, width, height, t0, t1):
        """`holoray render` into EXR files, read back by Blender's reader."""
        s = scene.holoray
        output = os.path.join(workdir, "out.exr")
        cmd, aovs = command(binary, scene, s, gltf, output, camera_object, width, height, self._lights_file)
        self._run(cmd)
        if self.test_break():
            return None
        t2 = time.perf_counter()
        result = self.begin_result(0, 0, width, height)
        layer = result.layers[0]
        if s.camera == "QUILT":  # holoray names a quilt by its layout: out_qsCxRaA.exr
            output = next(iter(glob.glob(os.path.join(workdir, "out_qs*.exr"))), output)
        # Blender's own EXR reader, then the pixels set whole. (RenderLayer.load_from_file
        # reads an EXR into Combined in 3.4 but leaves it black in 4.3.)
        _fill(layer.passes["Combined"], read_exr(output, width, height))
        for aov, name, channels, _, _ in self._PASSES:
            if aov in aovs and name in layer.passes:
                px = read_exr(f"{os.path.splitext(output)[0]}.{aov}.exr", width, height)
                _fill(layer.passes[name], px[:, :channels])
        self.end_result(result)
        t3 = time.perf_counter()
        preview.keep_last(output, s)  # for holoray.preview
        return (t0, t1, t2, t3), "program"

    def _render_in_process(self, hr, gltf, scene, camera_object, width, height, t0, t1):
        """holoray's Python module in this process: its arrays into the passes."""
        s = scene.holoray
        j = job.spec(scene, s, camera_object, width, height, self._lights_file)

        def progress(fraction):
            self.update_progress(fraction)
            if self.test_break():
                raise _Stopped

        try:
            res, warnings = inprocess.render(hr, gltf, j, progress)
        except _Stopped:
            return None
        except (hr.SceneError, ValueError, RuntimeError, OSError) as e:
            raise HolorayError(str(e)) from None
        if self.test_break():
            return None
        for w in warnings:
            self.report({"WARNING"}, f"holoray: {w}")
        t2 = time.perf_counter()
        colour = res.colour
        if colour.shape[:2] != (height, width):
            raise HolorayError(f"holoray made a {colour.shape[1]}x{colour.shape[0]} image, the render is {width}x{height}")
        result = self.begin_result(0, 0, width, height)
        layer = result.layers[0]
        # Blender's rows go bottom up; its float arrays take a (pixels, channels) buffer whole.
        rgba = np.empty((height, width, 4), dtype=np.float32)
        rgba[:, :, :3] = colour[::-1]
        rgba[:, :, 3] = 1
        _fill(layer.passes["Combined"], rgba.reshape(-1, 4))
        for aov, name, channels, _, _ in self._PASSES:
            if aov in res.aovs and name in layer.passes:
                _fill(layer.passes[name], res.aovs[aov][::-1].reshape(-1, channels))
        self.end_result(result)
        t3 = time.perf_counter()
        preview.keep_last_image(colour, hr.write_image, s)  # for holoray.preview, written when it asks
        return (t0, t1, t2, t3), "module"

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
