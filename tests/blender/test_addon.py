"""The Blender add-on (blender/holoray_blender) in Debian's Blender, headless:
the tests' scene (scene.py) is built and saved by case.py, then rendered as a
user renders it, `blender -b scene.blend --addons holoray_blender -E HOLORAY
-f 1`, with the holoray CLI found on PATH. Skipped where Blender is missing."""

import json
import os
import shutil
import signal
import subprocess
import time

import numpy as np
import pytest

import holoray

HERE = os.path.dirname(os.path.abspath(__file__))
BLENDER = shutil.which("blender")
pytestmark = pytest.mark.skipif(BLENDER is None, reason="Blender is not installed")


def env(with_holoray=True):
    e = dict(os.environ)
    cli_dir = os.path.dirname(os.path.abspath(os.environ["HOLORAY_CLI"]))
    path = [p for p in e.get("PATH", "").split(os.pathsep) if p and not os.path.isfile(os.path.join(p, "holoray"))]
    e["PATH"] = os.pathsep.join(([cli_dir] if with_holoray else []) + path)
    return e


def build(case, tmp_path):
    """Runs case.py in Blender: the saved scene, and its RESULT line."""
    run = subprocess.run([BLENDER, "-b", "--factory-startup", "--python", os.path.join(HERE, "case.py"), "--", case,
                          str(tmp_path)], env=env(), capture_output=True, text=True, timeout=300)
    lines = [l for l in run.stdout.splitlines() if l.startswith("RESULT ")]
    assert run.returncode == 0 and lines, run.stdout[-3000:] + run.stderr[-3000:]
    return json.loads(lines[-1][len("RESULT "):])


def render_args(tmp_path, backend=None, fmt="OPEN_EXR", device=None, gpu_device=None, python=None):
    """`blender -b scene.blend ... -f 1`, with scene.holoray.backend (and device, gpu_device) set first when given,
    and then the Python statement `python`."""
    sets = [f"bpy.context.scene.holoray.{k} = '{v}'"
            for k, v in (("backend", backend), ("device", device), ("gpu_device", gpu_device)) if v] + ([python] if python else [])
    expr = ["--python-expr", "import bpy; " + "; ".join(sets)] if sets else []
    return [BLENDER, "-b", str(tmp_path / "scene.blend"), "--addons", "holoray_blender", "-E", "HOLORAY"] + expr + [
        "-o", str(tmp_path / "frame_####"), "-F", fmt, "-f", "1"]


def render(tmp_path, with_holoray=True, backend=None, fmt="OPEN_EXR", device=None, gpu_device=None, python=None):
    run = subprocess.run(render_args(tmp_path, backend, fmt, device, gpu_device, python), env=env(with_holoray),
                         capture_output=True, text=True, timeout=300)
    return run.stdout + run.stderr


def test_the_eia_has_the_size_asked_for(tmp_path):
    assert build("eia", tmp_path)["resolution"] == [120, 80]  # 24x16 lenses x 5 px
    # A CPU render lists no Vulkan devices (that costs a Vulkan instance).
    listed = "import holoray_blender.devices as d; print('LISTED', d._listed is not None)"
    run = subprocess.run(render_args(tmp_path) + ["--python-expr", listed], env=env(), capture_output=True, text=True,
                         timeout=300)
    log = run.stdout + run.stderr
    assert "LISTED False" in log.splitlines(), log[-3000:]
    frame = holoray.read_image(tmp_path / "frame_0001.exr")
    assert frame.shape[:2] == (80, 120), log
    assert np.nanmax(frame[:, :, :3]) > 0.05, "the EIA is black"
    assert "Traceback" not in log


def test_the_module_in_blenders_process_and_the_program_give_the_same_render_result(tmp_path):
    # Colour and every pass: the arrays set straight into the render result
    # and the EXRs Blender reads back hold the same values, up to the last
    # bit that Blender's colour conversions move (reading the program's EXRs,
    # writing the frame: a 1.0 alpha comes out 0.99999994).
    build("both_ways", tmp_path)
    results = {}
    for backend in ("MODULE", "PROGRAM"):
        log = render(tmp_path, backend=backend, fmt="OPEN_EXR_MULTILAYER")
        assert f"({backend.lower()})" in log and "Traceback" not in log, log[-3000:]
        results[backend] = holoray.read_image(tmp_path / "frame_0001.exr")
        (tmp_path / "frame_0001.exr").unlink()
    module, program = results["MODULE"], results["PROGRAM"]
    # OpenEXR lists channels by name: Combined.A, B, G, R, Depth.Z, DiffCol.B, G, R, Normal.X, Y, Z.
    assert module.shape == program.shape == (80, 120, 11)
    assert np.array_equal(np.isnan(module), np.isnan(program))  # background depth
    both = ~np.isnan(module)
    assert np.abs(module[both] - program[both]).max() <= 1.2e-7 * max(1.0, np.abs(program[both]).max())
    assert (module[:, :, 0] == 1).all()  # alpha: the module's way sets it, Blender keeps it
    assert np.isfinite(module[:, :, 1:4]).all() and module[:, :, 1:4].max() > 0.05


def test_the_gpu_device_renders_the_cpus_eia_both_ways(tmp_path):
    # Device GPU, the first GPU (else lavapipe), through the module, and
    # GPU device 0 (lavapipe here) through the program: the CPU's EIA to
    # within float rounding (PSNR on the 8-bit scale), under Whitted's light
    # and under path tracing (the default; the two devices draw the same
    # samples).
    build("untextured", tmp_path)
    whitted = "bpy.context.scene.holoray.integrator = 'WHITTED'"
    log = render(tmp_path, python=whitted)
    cpu = holoray.read_image(tmp_path / "frame_0001.exr")[:, :, :3]
    for backend, gpu_device in (("MODULE", None), ("PROGRAM", "0")):
        (tmp_path / "frame_0001.exr").unlink()
        log = render(tmp_path, backend=backend, device="GPU", gpu_device=gpu_device, python=whitted)
        assert f"({backend.lower()})" in log and "Traceback" not in log, log[-3000:]
        gpu = holoray.read_image(tmp_path / "frame_0001.exr")[:, :, :3]
        assert gpu.shape == cpu.shape
        assert holoray.psnr(cpu, gpu) >= 50, backend
    path = "bpy.context.scene.holoray.samples = 4"
    (tmp_path / "frame_0001.exr").unlink()
    log = render(tmp_path, python=path)
    cpu = holoray.read_image(tmp_path / "frame_0001.exr")[:, :, :3]
    (tmp_path / "frame_0001.exr").unlink()
    log = render(tmp_path, backend="MODULE", device="GPU", python=path)
    assert "Traceback" not in log, log[-3000:]
    gpu = holoray.read_image(tmp_path / "frame_0001.exr")[:, :, :3]
    assert cpu.max() > 0.05 and holoray.psnr(cpu, gpu) >= 50


def test_the_gpu_menu_names_each_vulkan_device_holoray_lists(tmp_path):
    # Device GPU's GPU menu: the first GPU, then one item a device, named as
    # `holoray devices` names it; a scene set to one keeps it through a save
    # and a load (the .blend stores the item's number, the same next time).
    build("untextured", tmp_path)
    names = [line.split(": ", 1)[1].rsplit(", ", 3)[0] for line in holoray.gpu_devices()]
    assert names
    show = "print('ITEM', s.gpu_device, '|', bpy.types.UILayout.enum_item_name(s, 'gpu_device', s.gpu_device)); "
    expr = ("import bpy; s = bpy.context.scene.holoray; " + show +
            "".join(f"s.gpu_device = '{n}'; " + show for n in range(len(names))) +
            f"bpy.ops.wm.save_as_mainfile(filepath={str(tmp_path / 'saved.blend')!r})")
    reopen = "import bpy; s = bpy.context.scene.holoray; " + show
    log = ""
    for blend, python in (("scene.blend", expr), ("saved.blend", reopen)):
        run = subprocess.run([BLENDER, "-b", str(tmp_path / blend), "--addons", "holoray_blender", "--python-expr",
                              python], env=env(), capture_output=True, text=True, timeout=300)
        log += run.stdout + run.stderr
    items = [line for line in log.splitlines() if line.startswith("ITEM ")]
    last = len(names) - 1
    assert items == (["ITEM FIRST | First GPU"] + [f"ITEM {n} | {n}: {name}" for n, name in enumerate(names)] +
                     [f"ITEM {last} | {last}: {names[last]}"]), log[-3000:]


def test_a_gpu_device_this_machine_lacks_is_reported_and_the_first_gpu_renders(tmp_path):
    # A file that chose GPU device 50 (stored as 150), opened here: a
    # warning that names it, and the render on the first GPU all the same.
    build("untextured", tmp_path)
    run = subprocess.run(render_args(tmp_path, device="GPU", python="bpy.context.scene.holoray['gpu_device'] = 150"),
                         env=env(), capture_output=True, text=True, timeout=300)
    log = run.stdout + run.stderr
    assert ("Warning: holoray: the GPU device chosen in this file (number 50) is not on this machine: rendering on "
            "the first GPU (holoray devices lists this machine's)") in log.splitlines(), log[-3000:]
    assert holoray.read_image(tmp_path / "frame_0001.exr").shape[:2] == (80, 120), log[-3000:]


def test_disabling_the_addon_hands_back_the_gpu_device_the_module_kept(tmp_path):
    # After an in-process render on Device GPU the module keeps its device;
    # disabling the add-on releases it, so none is left to release after.
    build("untextured", tmp_path)
    after = ("import addon_utils, holoray; "
             "addon_utils.disable('holoray_blender'); print('LEFT', holoray.release_gpu_devices())")
    run = subprocess.run(render_args(tmp_path, backend="MODULE", device="GPU") + ["--python-expr", after], env=env(),
                         capture_output=True, text=True, timeout=300)
    log = run.stdout + run.stderr
    assert "(module)" in log and "Traceback" not in log, log[-3000:]
    assert "LEFT 0" in log.splitlines(), log[-3000:]


def test_the_shot_operators_array_is_the_one_f12_renders_with_a_lens_shift(tmp_path):
    r = build("shot_placement", tmp_path)
    assert r["centre"] < 1e-6 and r["normal"] < 1e-6 and r["width"] < 1e-6, r


def test_the_panel_shows_each_cameras_own_settings(tmp_path):
    shown = build("panel", tmp_path)
    assert {"grid", "lenses_x", "lenses_y", "pixels_per_lens", "fov_lens", "mode"} <= set(shown["INTEGRAL"])
    assert {"quilt_columns", "quilt_rows", "view_width", "view_height", "view_cone"} <= set(shown["QUILT"])
    assert "display_file" in shown["DISPLAY"]
    assert "calibration_file" in shown["LOOKING_GLASS"]
    own = {"INTEGRAL": "grid", "QUILT": "quilt_columns", "DISPLAY": "display_file", "LOOKING_GLASS": "calibration_file"}
    for cam, names in shown.items():
        assert names[0] == "camera" and "holoray.preview" in names, cam
        assert not (set(own.values()) - {own.get(cam)}) & set(names), cam  # no other camera's settings


def test_a_hex_eia_has_the_size_holoray_makes(tmp_path):
    # 24x16 lenses x 5 px: 16 rows of hexagons sqrt(3)/2 lens apart, 69 px (`holoray render --grid hex` says 120x69).
    assert build("hex", tmp_path)["resolution"] == [120, 69]
    log = render(tmp_path)
    assert "Error: holoray" not in log and "Traceback" not in log, log[-3000:]
    assert holoray.read_image(tmp_path / "frame_0001.exr").shape[:2] == (69, 120)


def test_a_quilt_has_its_views_size_times_its_layout(tmp_path):
    assert build("quilt", tmp_path)["resolution"] == [240, 160]  # 4x2 views of 60x80
    log = render(tmp_path)
    frame = holoray.read_image(tmp_path / "frame_0001.exr")
    assert frame.shape[:2] == (160, 240), log[-3000:]
    assert "Traceback" not in log


def test_shared_views_and_the_seed_reach_holoray_the_same_both_ways(tmp_path):
    # Shared views (path tracing, the default, on the CPU) and the seed
    # reach holoray through the module and through the program alike: the
    # same image, and not the unshared or unseeded one.
    build("quilt", tmp_path)
    images = {}
    for backend, share, seed in (("MODULE", 2, 0), ("PROGRAM", 2, 0), ("PROGRAM", 0, 0), ("MODULE", 0, 5), ("PROGRAM", 0, 5)):
        python = (f"bpy.context.scene.holoray.share_views = {share}; bpy.context.scene.holoray.seed = {seed}; "
                  "bpy.context.scene.holoray.samples = 4")
        log = render(tmp_path, backend=backend, python=python)
        assert f"({backend.lower()})" in log and "Traceback" not in log, log[-3000:]
        images[backend, share, seed] = holoray.read_image(tmp_path / "frame_0001.exr")[:, :, :3]
        (tmp_path / "frame_0001.exr").unlink()
    close = lambda a, b: np.abs(a - b).max() <= 1.2e-7 * max(1.0, np.abs(b).max())
    unshared = images["PROGRAM", 0, 0]
    assert close(images["MODULE", 2, 0], images["PROGRAM", 2, 0])
    assert np.abs(images["PROGRAM", 2, 0] - unshared).max() > 1e-3
    assert close(images["MODULE", 0, 5], images["PROGRAM", 0, 5])
    assert np.abs(images["PROGRAM", 0, 5] - unshared).max() > 1e-3


def test_the_array_stands_at_the_focus_distance_facing_the_camera(tmp_path):
    # A plane square to the view at the focus distance: every lens's centre
    # line meets it at the lens itself (line parameter t = 0).
    r = build("facing_plane_wide", tmp_path)
    assert r["lenses_hit"] == r["lenses"]
    assert r["max_abs_t"] < 1e-5


def test_the_array_spans_the_cameras_field_of_view(tmp_path):
    # The plane 1.05 times the view's width covers every lens (above); 0.8
    # times leaves the outer lenses of each side uncovered: 20 of 24 columns.
    r = build("facing_plane_narrow", tmp_path)
    assert r["edge_columns_hit"] == 0
    assert r["lenses_hit"] == 20 * 16


def albedo_psnr(a, b):
    """PSNR (dB, 8-bit scale) of two linear albedo images' RGB, clamped to 0..1."""
    return holoray.psnr(np.clip(a[:, :, :3], 0, 1), np.clip(b[:, :, :3], 0, 1))


def test_pinhole_matches_cycles_albedo_with_a_lens_shift(tmp_path):
    build("cycles", tmp_path)
    mine = holoray.read_image(tmp_path / "pinhole.albedo.exr")
    cycles = holoray.read_image(tmp_path / "pinhole_cycles.exr")
    assert mine.shape[:2] == cycles.shape[:2] == (120, 160)
    assert albedo_psnr(mine, cycles) >= 30


def test_the_eias_centre_view_matches_a_cycles_orthographic_view_at_the_array_with_a_lens_shift(tmp_path):
    build("cycles", tmp_path)
    eia = holoray.read_image(tmp_path / "eia.albedo.exr")
    view = holoray.light_field(eia, 5)[2, 2]  # 5 px per lens: pixel (2, 2) is each lens's centre
    cycles = holoray.read_image(tmp_path / "ortho_cycles.exr")
    assert view.shape[:2] == cycles.shape[:2] == (48, 64)
    assert albedo_psnr(view, cycles) >= 25


@pytest.mark.parametrize("case, message", [
    ("no_camera", "Error: Cannot render, no camera"),
    ("empty", "Error: holoray: the scene has nothing to render"),
    ("no_binary", "Error: holoray: the holoray program was not found"),
])
def test_a_scene_that_cannot_render_gives_an_error_report_not_a_traceback(tmp_path, case, message):
    build(case, tmp_path)
    log = render(tmp_path, with_holoray=case != "no_binary")
    assert message in log, log[-3000:]
    assert "Traceback" not in log, log[-3000:]
    assert not (tmp_path / "frame_0001.exr").exists()


def test_the_animation_operator_writes_the_frames_holoray_animate_writes_from_the_exported_shot(tmp_path):
    build("animation", tmp_path)
    run = subprocess.run([BLENDER, "-b", str(tmp_path / "scene.blend"), "--addons", "holoray_blender", "--python-expr",
                          "import bpy; bpy.ops.holoray.render_animation()"], env=env(), capture_output=True, text=True,
                         timeout=300)
    log = run.stdout + run.stderr
    assert "Traceback" not in log, log[-3000:]
    frames = sorted((tmp_path / "render").glob("*.png"))
    assert [f.name for f in frames] == [f"{n:04d}.png" for n in range(1, 7)], log[-3000:]
    shot = tmp_path / "render" / ".holoray" / "shot.toml"
    ref = tmp_path / "ref"
    subprocess.run([os.environ["HOLORAY_CLI"], "animate", str(shot), "-o", str(ref), "--frames", "1:6", "-q"], check=True)
    for n, f in enumerate(frames, start=1):
        assert f.read_bytes() == (ref / f"frame_{n:04d}.png").read_bytes(), f.name
    first, last = holoray.read_image(frames[0]), holoray.read_image(frames[-1])
    assert np.abs(first - last).max() > 0.1, "the cube did not move"


def test_the_centre_view_preview_is_the_eias_lens_centre_pixels(tmp_path):
    r = build("preview", tmp_path)
    assert r["size"] == [24, 16]
    assert r["max_difference"] < 1e-6


def test_export_web_writes_the_last_eias_page_as_holoray_web_does(tmp_path):
    r = build("export_web", tmp_path)
    assert r["files"] == ["eia.png", "holoray_web.js", "index.html", "light_field.json", "views.png"]
    m = r["manifest"]
    assert (m["kind"], m["grid"], m["pixels_per_lens"], m["lenses"], m["views"]) == ("eia", "square", 5, [24, 16], [5, 5])
    # The page's views are `holoray web`'s of the EIA Blender wrote (linear EXR: sRGB-encoded for the page).
    subprocess.run([os.environ["HOLORAY_CLI"], "web", str(tmp_path / "eia.exr"), "--pixels-per-lens", "5", "-q",
                    "-o", str(tmp_path / "ref")], check=True)
    assert np.array_equal(holoray.read_image(tmp_path / "page" / "views.png"), holoray.read_image(tmp_path / "ref" / "views.png"))


def holoray_processes(marker):
    """PIDs of holoray processes whose command line holds `marker` (their temporary folder)."""
    out = []
    for pid in os.listdir("/proc"):
        if pid.isdigit():
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    argv = f.read().split(b"\0")
            except OSError:
                continue
            if argv and os.path.basename(argv[0]) == b"holoray" and any(marker in a for a in argv):
                out.append(int(pid))
    return out


def test_a_cancelled_in_process_render_stops_and_writes_no_frame(tmp_path):
    build("large_module", tmp_path)
    blender = subprocess.Popen(render_args(tmp_path), env=env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
    log = []
    try:
        for line in blender.stdout:  # Blender prints the engine's stats lines headless
            log.append(line)
            if "tracing" in line:
                blender.send_signal(signal.SIGINT)  # Ctrl-C: Blender's break, what Esc is in the interface
                break
        log += blender.stdout.readlines()
        blender.wait(timeout=30)
    finally:
        if blender.poll() is None:
            blender.kill()
    text = "".join(log)
    assert "tracing" in text, text[-3000:]
    assert "Traceback" not in text, text[-3000:]
    assert "(module)" not in text, "the render finished: " + text[-3000:]
    assert not list(tmp_path.glob("frame_*"))


def test_a_cancelled_render_leaves_no_holoray_process(tmp_path):
    build("large", tmp_path)
    blender = subprocess.Popen(render_args(tmp_path), env=env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               text=True)
    try:
        deadline = time.monotonic() + 60
        while not holoray_processes(b"holoray-blender-") and time.monotonic() < deadline:
            time.sleep(0.05)
        assert holoray_processes(b"holoray-blender-"), "holoray never started"
        time.sleep(0.3)
        blender.send_signal(signal.SIGINT)  # Ctrl-C: Blender's break, what Esc is in the interface
        blender.wait(timeout=30)
    finally:
        if blender.poll() is None:
            blender.kill()
    time.sleep(0.2)
    assert holoray_processes(b"holoray-blender-") == []
    assert not list(tmp_path.glob("frame_*"))
