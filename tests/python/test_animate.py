"""holoray.animate yields the frames `holoray animate` writes.

examples/shots/swinging_box.toml: a glTF box sliding and turning, 48 frames
of 512x512 (64x64 lenses x 8 px), keyframes every 8 with reverse
reprojection between; the whole shot takes well under a second.
"""
from __future__ import annotations

import re
import tomllib

import numpy as np
import pytest

import holoray
from conftest import REPO, THREADS
from helpers import png_codes, read_image, srgb_encode

SHOT = REPO / "examples" / "shots" / "swinging_box.toml"
FRAMES = tomllib.loads(SHOT.read_text())["frames"]


@pytest.fixture(scope="module")
def cli_frames(tmp_path_factory, run_cli):
    """The CLI's whole shot: EXR frames (and its printed log), and PNG frames."""
    d = tmp_path_factory.mktemp("animate_cli")
    exr = run_cli("animate", SHOT, "-o", d / "exr", "--format", "exr", "--threads", THREADS)
    run_cli("animate", SHOT, "-o", d / "png", "--threads", THREADS, "-q")
    return d, exr.stdout


@pytest.fixture(scope="module")
def python_run(tmp_path_factory):
    """The module's whole shot, with output= a folder: [(index, colour, row)]."""
    out = tmp_path_factory.mktemp("animate_py")
    frames = list(holoray.animate(SHOT, output=out, threads=THREADS))
    return out, frames


def test_every_frame_is_yielded_once_in_order(python_run):
    _, frames = python_run
    assert [index for index, _, _ in frames] == list(range(FRAMES))


def test_yielded_frames_are_float32_rgb_of_the_array_size(python_run):
    _, frames = python_run
    for _, colour, row in frames:
        assert isinstance(colour, np.ndarray)
        assert colour.dtype == np.float32
        assert colour.shape == (512, 512, 3)
        assert isinstance(row, dict) and row
    assert frames[0][1].max() > 0


def test_yielded_colours_equal_the_cli_exr_frames(python_run, cli_frames):
    _, frames = python_run
    d, _ = cli_frames
    for index, colour, _ in frames:
        np.testing.assert_array_equal(colour, read_image(d / "exr" / f"frame_{index:04d}.exr"),
                                      err_msg=f"frame {index}")


def test_the_box_moves(python_run):
    _, frames = python_run
    assert not np.array_equal(frames[0][1], frames[-1][1])


def test_output_folder_holds_the_cli_png_frames(python_run, cli_frames):
    out, frames = python_run
    d, _ = cli_frames
    assert sorted(p.name for p in out.iterdir()) == [f"frame_{i:04d}.png" for i in range(FRAMES)]
    for index, _, _ in frames:
        name = f"frame_{index:04d}.png"
        np.testing.assert_array_equal(read_image(out / name), read_image(d / "png" / name),
                                      err_msg=name)


def test_written_png_is_the_yielded_colour_srgb_encoded(python_run):
    # A glTF shot: PNG codes are sRGB (--encoding auto), floor(255 v + 0.5).
    out, frames = python_run
    for index in (0, 5, FRAMES - 1):
        _, colour, _ = frames[index]
        codes = read_image(out / f"frame_{index:04d}.png") * 255
        expected = png_codes(srgb_encode(colour))
        diff = np.abs(codes - expected)
        assert diff.max() <= 1.0 + 1e-3, f"frame {index}: a code off by {diff.max()}"
        assert np.mean(diff < 1e-3) > 0.999, f"frame {index}: {np.mean(diff > 1e-3):.4%} codes differ"


def test_rows_name_their_frame_and_the_keyframes_the_cli_traced(python_run, cli_frames):
    _, frames = python_run
    _, log = cli_frames
    traced = {int(m.group(1)) for m in re.finditer(r"^frame\s+(\d+)\s+traced", log, re.M)}
    assert traced, log
    for index, _, row in frames:
        if "frame" in row:
            assert row["frame"] == index
        if "keyframe" in row:
            assert bool(row["keyframe"]) == (index in traced), (index, row)


def test_a_frame_range_yields_its_frames_equal_to_the_cli_range_and_the_whole_run(tmp, run_cli, python_run):
    _, whole = python_run
    run_cli("animate", SHOT, "-o", tmp / "cli", "--format", "exr", "--frames", "10:14", "--threads", THREADS, "-q")
    frames = list(holoray.animate(SHOT, frames="10:14", threads=THREADS))
    assert [index for index, _, _ in frames] == [10, 11, 12, 13, 14]
    for index, colour, _ in frames:
        np.testing.assert_array_equal(colour, read_image(tmp / "cli" / f"frame_{index:04d}.exr"))
        np.testing.assert_array_equal(colour, whole[index][1])


def test_method_full_equals_the_cli_full(tmp, run_cli):
    run_cli("animate", SHOT, "-o", tmp / "cli", "--format", "exr", "--frames", "0:3", "--method", "full",
            "--threads", THREADS, "-q")
    frames = list(holoray.animate(SHOT, frames="0:3", method="full", threads=THREADS))
    assert [index for index, _, _ in frames] == [0, 1, 2, 3]
    for index, colour, _ in frames:
        np.testing.assert_array_equal(colour, read_image(tmp / "cli" / f"frame_{index:04d}.exr"))


def test_pinhole_camera_option_equals_the_cli(tmp, run_cli):
    run_cli("animate", SHOT, "-o", tmp / "cli", "--format", "exr", "--frames", "0:2", "--camera", "pinhole",
            "--resolution", "48x32", "--threads", THREADS, "-q")
    frames = list(holoray.animate(SHOT, frames="0:2", camera=holoray.Pinhole(resolution=(48, 32)), threads=THREADS))
    assert [index for index, _, _ in frames] == [0, 1, 2]
    for index, colour, _ in frames:
        assert colour.shape == (32, 48, 3)
        np.testing.assert_array_equal(colour, read_image(tmp / "cli" / f"frame_{index:04d}.exr"))


def test_path_traced_frames_with_an_animated_seed_equal_the_cli(tmp, run_cli):
    # render()'s light keywords, and the seed: frame f of an animated seed S
    # is drawn with seed S + f, so the frames' noise differs where a fixed
    # seed's stays put.
    light = ("--integrator", "path", "--environment-colour", "0.3,0.4,0.5", "--seed", "5", "--animated-seed")
    run_cli("animate", SHOT, "-o", tmp / "cli", "--format", "exr", "--frames", "0:1", "--camera", "pinhole",
            "--resolution", "48x32", "--threads", THREADS, "-q", *light)
    options = dict(frames="0:1", camera=holoray.Pinhole(resolution=(48, 32)), threads=THREADS, integrator="path",
                   environment=(0.3, 0.4, 0.5), seed=5)
    animated = list(holoray.animate(SHOT, animated_seed=True, **options))
    for index, colour, _ in animated:
        np.testing.assert_array_equal(colour, read_image(tmp / "cli" / f"frame_{index:04d}.exr"))
    fixed = list(holoray.animate(SHOT, **options))
    np.testing.assert_array_equal(fixed[0][1], animated[0][1])  # frame 0: seed 5 either way
    assert not np.array_equal(fixed[1][1], animated[1][1])


def test_stopping_early_leaves_only_whole_frames(tmp):
    out = tmp / "out"
    it = holoray.animate(SHOT, output=out, threads=THREADS)
    seen = [next(it)[0] for _ in range(3)]
    it.close()
    assert seen == [0, 1, 2]
    names = sorted(p.name for p in out.iterdir())
    assert all(re.fullmatch(r"frame_\d{4}\.png", n) for n in names), names
    assert len(names) < FRAMES


def test_camera_name_reaches_the_shots_scene_files():
    # The shot's mesh file is read with the name given here: one it lacks is
    # refused, saying which cameras it has (none), before any frame.
    with pytest.raises(ValueError, match=r"swinging_box.gltf' has no camera 'nope' \(it has none\)"):
        next(holoray.animate(SHOT, camera_name="nope", frames=0, texture_path=["."]))
