"""holoray.light_field(eia, P)[v, u] is `holoray subaperture EIA --pixels-per-lens P --u u --v v`."""
from __future__ import annotations

import numpy as np
import pytest

import holoray
from conftest import THREADS
from helpers import read_image

NX, NY, P = 12, 8, 5  # rectangular, odd P: a swap of u and v, or of x and y, shows


@pytest.fixture(scope="module")
def eia_png(tmp_path_factory, run_cli, primitives_path):
    """A 60x40 EIA rendered by the CLI as an 8-bit PNG."""
    d = tmp_path_factory.mktemp("light_field")
    path = d / "eia.png"
    run_cli("render", primitives_path, "--lenses", f"{NX}x{NY}", "--pixels-per-lens", P, "--threads", THREADS,
            "-o", path)
    return path


def test_light_field_shape_is_p_p_ny_nx_c(eia_png):
    eia = read_image(eia_png)
    assert eia.shape == (NY * P, NX * P, 3)
    lf = holoray.light_field(eia, P)
    assert isinstance(lf, np.ndarray)
    assert lf.shape == (P, P, NY, NX, 3)
    assert lf.dtype == eia.dtype


def test_every_view_equals_cli_subaperture(tmp, run_cli, eia_png):
    eia = read_image(eia_png)
    lf = holoray.light_field(eia, P)
    assert eia.std() > 0.01, "the EIA should not be flat"
    for v in range(P):
        for u in range(P):
            out = tmp / f"view_{u}_{v}.png"
            run_cli("subaperture", eia_png, "--pixels-per-lens", P, "--u", u, "--v", v, "-o", out)
            view = read_image(out)
            assert view.shape == (NY, NX, 3)
            np.testing.assert_array_equal(lf[v, u], view, err_msg=f"view u={u} v={v}")


def test_default_cli_view_is_the_centre_pixel(tmp, run_cli, eia_png):
    out = tmp / "centre.png"
    run_cli("subaperture", eia_png, "--pixels-per-lens", P, "-o", out)
    lf = holoray.light_field(read_image(eia_png), P)
    np.testing.assert_array_equal(lf[P // 2, P // 2], read_image(out))


def test_view_u_v_takes_pixel_u_v_of_every_elemental_image():
    rng = np.random.default_rng(1)
    eia = rng.random((NY * P, NX * P, 3), dtype=np.float32)
    lf = holoray.light_field(eia, P)
    for v in range(P):
        for u in range(P):
            np.testing.assert_array_equal(lf[v, u], eia[v::P, u::P])
    # and lens (x, y)'s elemental image is lf[:, :, y, x]
    np.testing.assert_array_equal(lf[:, :, 3, 7], eia[3 * P:4 * P, 7 * P:8 * P])


def test_float_values_are_kept_exactly():
    eia = np.linspace(-1.0, 2.0, 4 * 4 * 6 * 4, dtype=np.float32).reshape(4 * 4, 6 * 4, 1)
    eia = np.concatenate([eia, eia * 3, -eia], axis=2)
    lf = holoray.light_field(eia, 4)
    assert lf.dtype == np.float32
    np.testing.assert_array_equal(np.sort(lf.ravel()), np.sort(eia.ravel()))


def test_a_two_dimensional_eia_gives_one_channel():
    rng = np.random.default_rng(2)
    eia = rng.random((3 * 4, 5 * 4), dtype=np.float32)
    lf = holoray.light_field(eia, 4)
    assert lf.shape in ((4, 4, 3, 5, 1), (4, 4, 3, 5)), lf.shape
    np.testing.assert_array_equal(lf.reshape(4, 4, 3, 5), holoray.light_field(eia[:, :, None], 4)[..., 0])


def test_four_channels_are_kept():
    rng = np.random.default_rng(3)
    eia = rng.random((2 * 3, 4 * 3, 4), dtype=np.float32)
    lf = holoray.light_field(eia, 3)
    assert lf.shape == (3, 3, 2, 4, 4)
    np.testing.assert_array_equal(lf[1, 2], eia[1::3, 2::3])


def test_non_contiguous_eia_gives_the_views_of_its_copy():
    rng = np.random.default_rng(4)
    big = rng.random((2 * 16, 24, 3), dtype=np.float32)
    strided = big[::2]
    assert not strided.flags.c_contiguous
    np.testing.assert_array_equal(holoray.light_field(strided, 4), holoray.light_field(strided.copy(), 4))


@pytest.mark.parametrize("shape", [(65, 64, 3), (64, 66, 3), (63, 63), (2, 4, 3)])
def test_size_not_a_multiple_of_p_raises_value_error(shape):
    with pytest.raises(ValueError):
        holoray.light_field(np.zeros(shape, np.float32), 4)


@pytest.mark.parametrize("p", [0, -4])
def test_non_positive_pixels_per_lens_raises_value_error(p):
    with pytest.raises(ValueError, match="pixels_per_lens"):
        holoray.light_field(np.zeros((16, 16, 3), np.float32), p)


@pytest.mark.parametrize("shape", [(16,), (2, 16, 16, 3)])
def test_eia_of_the_wrong_rank_raises_value_error(shape):
    with pytest.raises(ValueError, match="eia"):
        holoray.light_field(np.zeros(shape, np.float32), 4)
