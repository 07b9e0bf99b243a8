"""read_image / write_image round trips, and psnr against its definition and `holoray compare`."""
from __future__ import annotations

import math
import os
import re

import numpy as np
import pytest

import holoray
from helpers import png_codes, read_image, srgb_encode, write_image

RNG = np.random.default_rng(7)


@pytest.mark.parametrize("channels", [1, 3, 4])
def test_exr_round_trip_is_exact_for_float32(tmp, channels):
    image = RNG.normal(0.5, 2.0, (13, 17, channels)).astype(np.float32)
    image[0, 0, 0] = 1e-30   # tiny and huge values survive too
    image[1, 1, 0] = 3e38
    path = tmp / "a.exr"
    write_image(path, image)
    back = read_image(path)
    assert back.dtype == np.float32
    assert back.shape == image.shape
    np.testing.assert_array_equal(back, image)


def test_exr_keeps_nan_and_infinity(tmp):
    image = np.zeros((2, 3, 3), np.float32)
    image[0, 0] = np.nan
    image[0, 1] = np.inf
    image[0, 2] = -np.inf
    write_image(tmp / "a.exr", image)
    np.testing.assert_array_equal(read_image(tmp / "a.exr"), image)


@pytest.mark.parametrize("channels", [1, 3, 4])
def test_png_round_trip_is_within_half_a_code(tmp, channels):
    image = RNG.random((19, 11, channels), dtype=np.float32)
    path = tmp / "a.png"
    write_image(path, image)
    back = read_image(path)
    assert back.dtype == np.float32 and back.shape == image.shape
    assert np.abs(back - image).max() <= 0.5 / 255 + 1e-6
    # and the values read are 8-bit codes / 255, the codes floor(255 v + 0.5)
    np.testing.assert_allclose(back * 255, png_codes(image), atol=1e-3)


def test_png_values_outside_0_1_are_clamped(tmp):
    image = np.array([[[-0.5, 0.0, 1.0], [1.5, 7.0, -1e9]]], np.float32)
    write_image(tmp / "c.png", image)
    np.testing.assert_array_equal(read_image(tmp / "c.png"), np.clip(image, 0, 1))


def test_srgb_png_holds_the_srgb_codes(tmp):
    image = RNG.random((16, 16, 3), dtype=np.float32)
    write_image(tmp / "s.png", image, encoding="srgb")
    back = read_image(tmp / "s.png")  # codes / 255, not decoded
    assert np.abs(back - srgb_encode(image)).max() <= 0.5 / 255 + 1e-5
    assert np.mean(np.rint(back * 255) == png_codes(srgb_encode(image))) > 0.999


def test_read_and_write_take_path_objects_and_strings(tmp):
    image = RNG.random((4, 5, 3), dtype=np.float32)
    holoray.write_image(tmp / "p.exr", image)              # pathlib.Path (os.PathLike)
    holoray.write_image(str(tmp / "s.exr"), image)         # str
    np.testing.assert_array_equal(holoray.read_image(tmp / "s.exr"), image)
    np.testing.assert_array_equal(holoray.read_image(str(tmp / "p.exr")), image)


def test_write_image_leaves_only_the_file(tmp):
    write_image(tmp / "only.exr", np.ones((4, 4, 3), np.float32))
    write_image(tmp / "only.png", np.ones((4, 4, 3), np.float32))
    assert sorted(p.name for p in tmp.iterdir()) == ["only.exr", "only.png"]


def test_write_image_replaces_an_existing_file(tmp):
    write_image(tmp / "r.exr", np.ones((4, 4, 3), np.float32))
    write_image(tmp / "r.exr", np.full((2, 3, 3), 0.25, np.float32))
    np.testing.assert_array_equal(read_image(tmp / "r.exr"), np.full((2, 3, 3), 0.25, np.float32))


def test_write_image_takes_non_contiguous_and_float64_arrays(tmp):
    image = RNG.random((8, 10, 3))  # float64
    strided = image[:, ::2]
    assert not strided.flags.c_contiguous
    write_image(tmp / "n.exr", strided)
    np.testing.assert_array_equal(read_image(tmp / "n.exr"), strided.astype(np.float32))


def test_images_written_by_the_module_are_read_by_the_cli(tmp, run_cli):
    a = RNG.random((12, 10, 3), dtype=np.float32)
    write_image(tmp / "a.exr", a)
    out = tmp / "view.exr"
    # a 12x10 image as an EIA of 1 px per lens: its only view is itself
    run_cli("subaperture", tmp / "a.exr", "--pixels-per-lens", 1, "-o", out)
    np.testing.assert_array_equal(read_image(out), a)


def test_psnr_of_equal_images_is_infinite():
    a = RNG.random((8, 8, 3))
    assert holoray.psnr(a, a.copy()) == math.inf


def test_psnr_of_a_one_code_offset_is_20_log10_255():
    a = RNG.uniform(0.1, 0.8, (32, 24, 3))
    expected = 20 * math.log10(255)  # 48.1308 dB: MSE 1 on the 8-bit scale
    assert holoray.psnr(a, a + 1 / 255) == pytest.approx(expected, abs=1e-3)
    assert holoray.psnr(a + 1 / 255, a) == pytest.approx(expected, abs=1e-3)


def test_psnr_follows_its_definition():
    a = RNG.random((20, 30, 3))
    b = np.clip(a + RNG.normal(0, 0.03, a.shape), 0, 1)
    mse = np.mean((255 * (a.astype(np.float32) - b.astype(np.float32)).astype(np.float64)) ** 2)
    assert holoray.psnr(a, b) == pytest.approx(10 * math.log10(255**2 / mse), abs=1e-3)


def test_psnr_ignores_alpha():
    a = RNG.random((6, 6, 4))
    b = a.copy()
    b[..., 3] = 0
    assert holoray.psnr(a, b) == math.inf


def test_psnr_agrees_with_cli_compare(tmp, run_cli):
    a = RNG.random((24, 16, 3), dtype=np.float32)
    b = np.clip(a + RNG.normal(0, 0.02, a.shape).astype(np.float32), 0, 1)
    write_image(tmp / "a.exr", a)
    write_image(tmp / "b.exr", b)
    out = run_cli("compare", tmp / "a.exr", tmp / "b.exr").stdout
    m = re.search(r"^all\s+\S+\s+\S+\s+(\S+)", out, re.M)
    assert m, out
    assert holoray.psnr(a, b) == pytest.approx(float(m.group(1)), abs=6e-4)  # printed to 3 decimals


def test_the_path_integrator_renders_from_python_as_from_the_cli(tmp_path):
    """integrator='path' with an environment colour: the same image as the CLI's
    (one sampler, one seed per pixel), and the furnace's value on a white-sky
    Lambertian sphere."""
    import subprocess
    nff = tmp_path / "s.nff"
    nff.write_text("v\nfrom 0 -4 0\nat 0 0 0\nup 0 0 1\nangle 40\nhither 0\nresolution 24 24\n"
                   "f 0.5 0.5 0.5 1 0 0 0 1\ns 0 0 0 1\n")
    scene = holoray.load_scene(str(nff))
    cam = holoray.Pinhole(resolution=(24, 24))
    res = holoray.render(scene, cam, spp=16, integrator="path", environment=(1, 1, 1))
    assert abs(float(res.colour[12, 12, 0]) - 0.5) < 0.05
    assert float(res.colour[0, 0, 0]) == 1.0
    out = tmp_path / "cli.exr"
    subprocess.run([os.environ["HOLORAY_CLI"], "render", str(nff), "--camera", "pinhole", "--resolution", "24x24",
                    "--spp", "16", "--integrator", "path", "--environment-colour", "1,1,1", "-q", "-o", str(out)], check=True)
    assert np.array_equal(holoray.read_image(str(out))[:, :, :3], res.colour)
    with pytest.raises(ValueError, match="integrator: expected 'whitted' or 'path', got 'pbrt'"):
        holoray.render(scene, cam, integrator="pbrt")
    with pytest.raises(ValueError, match="environment: lights the path integrator only"):
        holoray.render(scene, cam, environment=(1, 1, 1))
