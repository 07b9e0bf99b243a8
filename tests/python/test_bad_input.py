"""Bad input raises the exception the stub names, with a message that says where and what."""
from __future__ import annotations

import json
import re
import time

import numpy as np
import pytest

import holoray
from conftest import REPO, THREADS
from helpers import read_image, vm_rss_bytes, write_image

NFF_HEAD = ("v\nfrom 0 -10 5\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0.01\nresolution 64 64\n"
            "b 0 0 0\nl 1 1 10\nf 1 0 0 1 0 0 0 1\n")  # 10 lines


def write(path, text):
    path.write_text(text)
    return path


def small_camera():
    return holoray.LensArray(lenses=(4, 4), pixels_per_lens=4)


@pytest.fixture
def scene():
    s = holoray.Scene()
    s.add_sphere((0, 0, 0), 1)
    s.set_viewpoint((0, -5, 0), (0, 0, 0), (0, 0, 1), 40)
    return s


def render_raises(exc, scene, camera_factory, match=None, **kwargs):
    """The error may come from the camera's constructor or from render: both are inside."""
    with pytest.raises(exc, match=match) as info:
        holoray.render(scene, camera_factory(), threads=THREADS, **kwargs)
    return info


# ---- scene files ------------------------------------------------------------

def test_scene_error_is_a_value_error():
    assert issubclass(holoray.SceneError, ValueError)


def test_malformed_nff_raises_scene_error_at_file_line_col(tmp):
    path = write(tmp / "bad.nff", NFF_HEAD + "s 0 0 zz 1\n")  # line 11, 'zz' at column 7
    with pytest.raises(holoray.SceneError) as info:
        holoray.load_scene(path)
    e = info.value
    assert e.line == 11
    assert e.column == 7
    assert f"{path}:11:7:" in str(e), str(e)
    assert "error" in str(e)
    assert "zz" in str(e)
    assert str(e.file) == str(path) or str(e.file).endswith("bad.nff")
    # the offending line and a caret under the column
    lines = str(e).splitlines()
    caret_line = next(l for l in lines if l.strip() == "^")
    source_line = lines[lines.index(caret_line) - 1]
    assert source_line.strip() == "s 0 0 zz 1"
    assert source_line[caret_line.index("^")] == "z"


def test_sphere_missing_its_radius_is_reported_at_the_end_of_its_line(tmp):
    path = write(tmp / "short.nff", NFF_HEAD + "s 0 0 0\n")
    with pytest.raises(holoray.SceneError) as info:
        holoray.load_scene(str(path))
    e = info.value
    assert e.line == 11
    assert e.column == len("s 0 0 0") + 1
    assert f"{path}:11:{e.column}:" in str(e)
    assert "radius" in str(e)


def test_scene_error_position_matches_the_cli(tmp, run_cli):
    path = write(tmp / "bad.nff", NFF_HEAD + "p 3\n0 0 0\n1 0 0\n1 1 oops\n")
    cli = run_cli("render", path, "-o", tmp / "x.png", ok=False)
    assert cli.returncode == 1
    with pytest.raises(holoray.SceneError) as info:
        holoray.load_scene(path)
    m = re.search(re.escape(str(path)) + r":(\d+):(\d+): error: (.*)", cli.stderr)
    assert m, cli.stderr
    assert (info.value.line, info.value.column) == (int(m.group(1)), int(m.group(2))) == (14, 5)
    assert m.group(0) in str(info.value)


def test_missing_scene_file_raises_file_not_found(tmp):
    with pytest.raises(FileNotFoundError) as info:
        holoray.load_scene(tmp / "nothere.nff")
    assert "nothere.nff" in str(info.value)


def test_malformed_mesh_file_raises_scene_error_naming_the_file(tmp, run_cli):
    # A face names vertex 9 of 3: assimp refuses it; the one error rule makes
    # it a SceneError (no position: the message is assimp's), as in the CLI.
    path = write(tmp / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    with pytest.raises(holoray.SceneError) as info:
        holoray.load_scene(path)
    assert info.value.file == str(path)
    assert (info.value.line, info.value.column) == (0, 0)
    cli = run_cli("render", path, "-o", tmp / "x.png", ok=False)
    assert cli.returncode == 1
    assert f"holoray: error: {info.value}" in cli.stderr


def test_malformed_gltf_structure_raises_scene_error(tmp):
    path = write(tmp / "m.gltf", '{"asset": {"version": "2.0"}, "accessors": '
                                 '[{"componentType": 5126, "count": 0, "type": "SCALAR"}]}')
    with pytest.raises(holoray.SceneError) as info:
        holoray.load_scene(path)
    assert str(info.value) == f"cannot read '{path}': /accessors/0/count must be an integer of at least 1"


def test_folder_as_scene_file_raises_is_a_directory(tmp):
    with pytest.raises(IsADirectoryError) as info:
        holoray.load_scene(tmp)
    assert str(tmp) in str(info.value)


def test_missing_display_and_calibration_files_raise_file_not_found(tmp, scene):
    for make in (lambda: holoray.Display(tmp / "nothere.toml"), lambda: holoray.LookingGlass(tmp / "nothere.json")):
        with pytest.raises(FileNotFoundError) as info:
            holoray.render(scene, make(), threads=THREADS)
        assert "nothere" in str(info.value)


def test_malformed_display_file_raises_scene_error(tmp, scene):
    path = write(tmp / "d.toml", '[panel]\nresolution = [64, 48]\npixel_pitch_mm = 0.1\nsubpixels = "none"\n'
                                 '[lens]\ngrid = "squar"\npitch_mm = 0.4\nfocal_length_mm = 1.0\n')
    with pytest.raises(holoray.SceneError) as info:
        holoray.render(scene, holoray.Display(path), threads=THREADS)
    assert (info.value.line, info.value.column) == (6, 8)
    assert f"{path}:6:8:" in str(info.value)


def test_malformed_calibration_raises_scene_error(tmp, scene):
    path = write(tmp / "c.json", '{\n  "pitch": {"value": 52.56},\n  "slope": {"value": "x"}\n}\n')
    with pytest.raises(holoray.SceneError) as info:
        holoray.render(scene, holoray.LookingGlass(path), threads=THREADS)
    assert "c.json" in str(info.value) and "slope" in str(info.value)


def test_malformed_shot_raises_scene_error(tmp, repo):
    path = write(tmp / "s.toml", f'frames = 3\n[array]\nlenses = [8, 8]\nbogus = 1\n[[object]]\n'
                                 f'scene = "{repo / "examples" / "primitives.nff"}"\n')
    with pytest.raises(holoray.SceneError) as info:
        next(iter(holoray.animate(path, output=tmp / "out")))
    assert (info.value.line, info.value.column) == (4, 1)
    assert "bogus" in str(info.value)


def test_animation_rules_name_the_keywords(repo):
    # The API refuses `Pinhole` with `method` reverse; Python reads its own
    # words (the CLI reads --camera pinhole and --method: tests/test_pinhole.cpp).
    with pytest.raises(ValueError) as info:
        next(iter(holoray.animate(repo / "examples" / "shots" / "swinging_box.toml", camera=holoray.Pinhole(),
                                  method="reverse")))
    assert str(info.value) == "Pinhole: goes with method full (reuse works on elemental images)"
    with pytest.raises(ValueError) as info:
        next(iter(holoray.animate(repo / "examples" / "shots" / "swinging_box.toml", camera=holoray.Pinhole(),
                                  method="full", report=True)))
    assert str(info.value) == "report: goes with the integral camera (pinhole previews are traced in full)"


def test_missing_shot_raises_file_not_found(tmp):
    with pytest.raises(FileNotFoundError):
        next(iter(holoray.animate(tmp / "nothere.toml")))


# ---- meshes from arrays -------------------------------------------------------

V = np.array([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)], dtype=np.float64)
F = np.array([(0, 1, 2), (1, 3, 2)], dtype=np.int32)


def _nan(v, value):
    v = v.copy()
    v[2, 1] = value
    return v


BAD_MESHES = {
    "vertices_n_by_2": (ValueError, "vertices", dict(vertices=V[:, :2], faces=F)),
    "vertices_n_by_4": (ValueError, "vertices", dict(vertices=np.hstack([V, V[:, :1]]), faces=F)),
    "vertices_flat": (ValueError, "vertices", dict(vertices=V.ravel(), faces=F)),
    "vertices_nan": (ValueError, "vertices", dict(vertices=_nan(V, np.nan), faces=F)),
    "vertices_inf": (ValueError, "vertices", dict(vertices=_nan(V, np.inf), faces=F)),
    "vertices_minus_inf": (ValueError, "vertices", dict(vertices=_nan(V, -np.inf), faces=F)),
    "faces_float": (TypeError, "faces", dict(vertices=V, faces=F.astype(np.float64))),
    "faces_n_by_4": (ValueError, "faces", dict(vertices=V, faces=np.array([(0, 1, 3, 2)]))),
    "faces_index_too_large": (ValueError, "faces", dict(vertices=V, faces=np.array([(0, 1, 4)]))),
    "faces_index_negative": (ValueError, "faces", dict(vertices=V, faces=np.array([(0, -1, 2)]))),
    "normals_wrong_count": (ValueError, "normals", dict(vertices=V, faces=F, normals=np.tile([0.0, 0, 1], (3, 1)))),
    "normals_n_by_2": (ValueError, "normals", dict(vertices=V, faces=F, normals=np.zeros((4, 2)))),
    "normals_nan": (ValueError, "normals", dict(vertices=V, faces=F, normals=np.full((4, 3), np.nan))),
    "uv_n_by_3": (ValueError, "uv", dict(vertices=V, faces=F, uv=np.zeros((4, 3)),
                                          texture=np.ones((2, 2, 3), np.float32))),
    "uv_wrong_count": (ValueError, "uv", dict(vertices=V, faces=F, uv=np.zeros((5, 2)),
                                               texture=np.ones((2, 2, 3), np.float32))),
    "texture_two_channels": (ValueError, "texture", dict(vertices=V, faces=F, uv=np.zeros((4, 2)),
                                                          texture=np.ones((2, 2, 2), np.float32))),
    "texture_flat": (ValueError, "texture", dict(vertices=V, faces=F, uv=np.zeros((4, 2)),
                                                  texture=np.ones((4,), np.float32))),
}


@pytest.mark.parametrize("case", list(BAD_MESHES))
def test_bad_mesh_array_raises_naming_the_argument(case):
    exc, argument, kwargs = BAD_MESHES[case]
    scene = holoray.Scene()
    with pytest.raises(exc) as info:
        scene.add_mesh(**kwargs)
    assert argument in str(info.value), str(info.value)
    assert scene.object_count == 0, "a refused mesh must not be added"


def test_a_good_mesh_after_a_refused_one_is_added():
    scene = holoray.Scene()
    with pytest.raises(ValueError):
        scene.add_mesh(V[:, :2], F)
    scene.add_mesh(V, F)
    assert scene.object_count == 1


# ---- cameras and render options ----------------------------------------------


def test_library_messages_name_the_api_not_the_cli_options(tmp):
    # The library names a camera by the API's type (`Quilt`), which the CLI
    # says as --quilt: Python reads the class name.
    j = json.loads((REPO / "tests" / "data" / "blender" / "mapped_plane.gltf").read_text())
    j["cameras"] = [{"type": "orthographic", "name": "top",
                     "orthographic": {"xmag": 2.0, "ymag": 2.0, "znear": 0.1, "zfar": 100.0}}]
    path = tmp / "ortho.gltf"
    path.write_text(json.dumps(j))
    scene = holoray.load_scene(path)
    with pytest.raises(ValueError) as info:
        holoray.render(scene, holoray.Quilt(2, 2, view_resolution=(8, 8)), threads=THREADS)
    assert str(info.value).startswith("Quilt: the camera ")
    assert "--" not in str(info.value)

def test_absurd_lens_array_is_refused_quickly_before_allocating(scene):
    rss = vm_rss_bytes()
    start = time.monotonic()
    with pytest.raises(ValueError) as info:
        holoray.render(scene, holoray.LensArray(lenses=(100000, 100000), pixels_per_lens=64), threads=THREADS)
    elapsed = time.monotonic() - start
    assert elapsed < 1.0, f"took {elapsed:.2f} s to refuse"
    assert vm_rss_bytes() - rss < 64 * 2**20
    assert "6400000x6400000" in str(info.value), str(info.value)


BAD_CAMERAS = {
    "pixels_per_lens_zero": ("pixels_per_lens", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=0)),
    "pixels_per_lens_negative": ("pixels_per_lens", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=-2)),
    "lenses_zero": ("lenses", lambda: holoray.LensArray(lenses=(0, 4), pixels_per_lens=4)),
    "grid_unknown": ("grid", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, grid="triangular")),
    "mode_unknown": ("mode", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, mode="sideways")),
    "fov_lens_180": ("fov_lens", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, fov_lens=180)),
    "fov_lens_nan": ("fov_lens", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, fov_lens=float("nan"))),
    "pitch_negative": ("pitch", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, pitch=-1.0)),
    "gap_zero": ("gap", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, gap=0.0)),
    "rows_zero": ("rows", lambda: holoray.LensArray(lenses=(4, 4), pixels_per_lens=4, grid="hex", rows=0)),
    "pinhole_resolution_zero": ("resolution", lambda: holoray.Pinhole(resolution=(0, 16))),
    "quilt_columns_zero": ("columns", lambda: holoray.Quilt(0, 2, view_resolution=(8, 8))),
    "quilt_rows_zero": ("rows", lambda: holoray.Quilt(2, 0, view_resolution=(8, 8))),
    "quilt_view_cone_negative": ("view_cone", lambda: holoray.Quilt(2, 2, view_resolution=(8, 8), view_cone=-5)),
    "looking_glass_views_zero": ("views", lambda: holoray.LookingGlass(
        REPO / "examples" / "displays" / "looking_glass_example_calibration.json", views=0)),
}


@pytest.mark.parametrize("case", list(BAD_CAMERAS))
def test_bad_camera_raises_value_error_naming_the_argument(scene, case):
    argument, make = BAD_CAMERAS[case]
    info = render_raises(ValueError, scene, make)
    assert argument in str(info.value), str(info.value)


BAD_OPTIONS = {
    "aovs_unknown": ("aovs", dict(aovs=("albedo", "colour_of_magic"))),
    "threads_negative": ("threads", dict(threads=-1)),
    "spp_zero": ("spp", dict(spp=0)),
    "max_depth_zero": ("max_depth", dict(max_depth=0)),
    "max_depth_17": ("max_depth", dict(max_depth=17)),
}


@pytest.mark.parametrize("case", list(BAD_OPTIONS))
def test_bad_render_option_raises_value_error_naming_it(scene, case):
    argument, kwargs = BAD_OPTIONS[case]
    with pytest.raises(ValueError) as info:
        holoray.render(scene, small_camera(), **{"threads": THREADS, **kwargs})
    assert argument in str(info.value), str(info.value)


def test_a_scene_without_viewpoint_cannot_place_a_lens_array():
    s = holoray.Scene()
    s.add_sphere((0, 0, 0), 1)
    with pytest.raises(ValueError):
        holoray.render(s, small_camera(), threads=THREADS)


def test_render_of_something_that_is_not_a_camera_raises_type_error(scene):
    with pytest.raises(TypeError):
        holoray.render(scene, "lens array", threads=THREADS)
    with pytest.raises(TypeError):
        holoray.render("scene.nff", small_camera(), threads=THREADS)


def test_bad_animate_option_raises_value_error_naming_it(tmp, repo):
    shot = repo / "examples" / "shots" / "swinging_box.toml"
    for option, value in (("method", "guess"), ("fill", "paint"), ("reach", "far"), ("keyframe_interval", -3),
                          ("frames", "7:3"), ("frames", "40:60"), ("threads", -1), ("integrator", "radiosity"),
                          ("environment", (1, 2)), ("seed", -1), ("seed", 2**32), ("animated_seed", True)):
        with pytest.raises(ValueError) as info:
            next(iter(holoray.animate(shot, output=tmp / "out", **{option: value})))
        assert option in str(info.value) or option.replace("_", "-") in str(info.value), (option, str(info.value))
    with pytest.raises((TypeError, ValueError)) as info:
        next(iter(holoray.animate(shot, output=tmp / "out", no_such_option=1)))
    assert "no_such_option" in str(info.value)


# ---- images -----------------------------------------------------------------

def test_missing_image_raises_file_not_found(tmp):
    with pytest.raises(FileNotFoundError) as info:
        read_image(tmp / "nothere.png")
    assert "nothere.png" in str(info.value)


def test_unreadable_image_raises_naming_the_file(tmp):
    # The stub names no exception for this; any of the usual ones, with the file's name.
    path = write(tmp / "junk.png", "this is not an image\n")
    with pytest.raises((ValueError, OSError, RuntimeError)) as info:
        read_image(path)
    assert "junk.png" in str(info.value)


def test_write_image_unknown_encoding_raises_value_error(tmp):
    with pytest.raises(ValueError, match="encoding"):
        write_image(tmp / "a.png", np.zeros((4, 4, 3), np.float32), encoding="gamma22")
    assert list(tmp.iterdir()) == [], "a refused write leaves no file"


def test_write_image_unknown_extension_raises_value_error(tmp):
    with pytest.raises(ValueError) as info:
        write_image(tmp / "a.xyz", np.zeros((4, 4, 3), np.float32))
    assert ".xyz" in str(info.value)
    assert list(tmp.iterdir()) == []


@pytest.mark.parametrize("shape", [(4, 4, 5), (4, 4, 0), (0, 4, 3), (4,)])
def test_write_image_bad_shape_raises_value_error(tmp, shape):
    with pytest.raises(ValueError):
        write_image(tmp / "a.exr", np.zeros(shape, np.float32))
    assert list(tmp.iterdir()) == []


def test_psnr_of_different_sizes_raises_value_error():
    with pytest.raises(ValueError):
        holoray.psnr(np.zeros((4, 4, 3)), np.zeros((4, 5, 3)))
