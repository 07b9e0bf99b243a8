"""The preview tools on numpy arrays agree with independent paths: numpy's
slicing of the EIA (subaperture_view) and the CLI's own commands (simulate,
interlace), whose files are the 8-bit codes of the same values."""
from __future__ import annotations

import numpy as np
import pytest

import holoray
from conftest import REPO, THREADS
from helpers import read_image

NX, NY, P = 12, 8, 5
DISPLAY = REPO / "examples" / "displays" / "lenticular_4k.toml"
CALIBRATION = REPO / "examples" / "displays" / "looking_glass_example_calibration.json"


@pytest.fixture(scope="module")
def eia(tmp_path_factory, run_cli, primitives_path):
    path = tmp_path_factory.mktemp("preview_tools") / "eia.png"
    run_cli("render", primitives_path, "--lenses", f"{NX}x{NY}", "--pixels-per-lens", P, "--threads", THREADS,
            "-o", path)
    return read_image(path)


def as_png(tmp, name, image):
    """`image` as the CLI's PNG holds it: its 8-bit codes / 255."""
    holoray.write_image(tmp / name, image)
    return read_image(tmp / name)


def test_subaperture_view_is_the_slice_of_every_lens(eia):
    assert eia.std() > 0.01, "the EIA should not be flat"
    for u, v in [(0, 0), (P - 1, 1), (2, P - 1)]:
        view = holoray.subaperture_view(eia, P, u=u, v=v)
        assert view.shape == (NY, NX, 3)
        np.testing.assert_array_equal(view, eia[v::P, u::P])
    np.testing.assert_array_equal(holoray.subaperture_view(eia, P), eia[P // 2::P, P // 2::P])


def test_subaperture_view_refuses_part_lenses_and_unknown_grids(eia):
    with pytest.raises(ValueError, match="not a multiple of 7 pixels per lens"):
        holoray.subaperture_view(eia, 7)
    with pytest.raises(ValueError, match="grid: expected one of square, hex, lenticular, got 'tri'"):
        holoray.subaperture_view(eia, P, grid="tri")


def test_simulate_view_is_what_holoray_simulate_writes(tmp, run_cli):
    rng = np.random.default_rng(7)
    panel = rng.random((2160, 3840, 3), dtype=np.float32)
    holoray.write_image(tmp / "panel.png", panel)
    panel = read_image(tmp / "panel.png")
    run_cli("simulate", tmp / "panel.png", "--display", DISPLAY, "--eye", "-40,0,600", "--width", 160,
            "-o", tmp / "seen.png")
    seen = holoray.simulate_view(panel, DISPLAY, eye=(-40, 0, 600), width=160)
    np.testing.assert_array_equal(as_png(tmp, "mine.png", seen), read_image(tmp / "seen.png"))


def test_interlace_quilt_is_what_holoray_interlace_writes(tmp, run_cli):
    rng = np.random.default_rng(11)
    quilt = rng.random((2 * 24, 3 * 16, 3), dtype=np.float32)
    holoray.write_image(tmp / "q_qs3x2a0.67.png", quilt)
    quilt = read_image(tmp / "q_qs3x2a0.67.png")
    run_cli("interlace", tmp / "q_qs3x2a0.67.png", "--looking-glass", CALIBRATION, "-o", tmp / "panel.png")
    panel = holoray.interlace_quilt(quilt, 3, 2, CALIBRATION)
    np.testing.assert_array_equal(as_png(tmp, "mine.png", panel), read_image(tmp / "panel.png"))
    with pytest.raises(ValueError, match="a 48x48 image is not 5x2 views of whole pixels"):
        holoray.interlace_quilt(quilt, 5, 2, CALIBRATION)
