"""holoray.render(..., device="gpu"): the GPU path from Python.

On lavapipe where there is no GPU (setup.sh installs mesa-vulkan-drivers):
the GPU's image agrees with the CPU's (PSNR on the 8-bit scale, the id AOV),
path traced too,
stats name the device, and bad values raise ValueError naming `device`.
"""
from __future__ import annotations

import numpy as np
import pytest

import holoray
from conftest import REPO


def psnr_8bit(a: np.ndarray, b: np.ndarray) -> float:
    mse = float(np.mean((np.clip(a, 0, 1) * 255.0 - np.clip(b, 0, 1) * 255.0) ** 2))
    return float("inf") if mse == 0 else 10 * np.log10(255.0**2 / mse)


def test_gpu_image_agrees_with_the_cpu_image():
    scene = holoray.load_scene(str(REPO / "examples" / "primitives.nff"))
    camera = holoray.LensArray(lenses=(24, 24), pixels_per_lens=6)
    cpu = holoray.render(scene, camera, aovs=["id"])
    gpu = holoray.render(scene, camera, aovs=["id"], device="gpu")
    assert gpu.colour.shape == cpu.colour.shape
    assert psnr_8bit(cpu.colour, gpu.colour) >= 50
    assert np.mean(gpu.aovs["id"] == cpu.aovs["id"]) >= 0.999
    assert cpu.stats["device"] == "cpu"
    assert "(Vulkan 1." in gpu.stats["device"]
    assert gpu.stats["rays"]["eye"] > 0
    assert cpu.stats["seconds"]["gpu_setup"] == 0
    assert 0 < gpu.stats["seconds"]["gpu_setup"] <= gpu.stats["seconds"]["build"]


def test_path_tracing_on_the_gpu_agrees_with_the_cpu():
    # The two devices draw the same samples (tests/test_gpu_light.cpp): an
    # environment given as a colour, through Python's keywords.
    scene = holoray.load_scene(str(REPO / "examples" / "primitives.nff"))
    camera = holoray.Pinhole(resolution=(40, 30))
    light = dict(integrator="path", environment=(0.3, 0.4, 0.5), spp=8)
    cpu = holoray.render(scene, camera, **light)
    gpu = holoray.render(scene, camera, device="gpu", **light)
    assert cpu.colour.mean() > 0.05
    assert psnr_8bit(cpu.colour, gpu.colour) >= 50


def test_bad_device_names_the_keyword():
    scene = holoray.load_scene(str(REPO / "examples" / "primitives.nff"))
    with pytest.raises(ValueError, match=r"^device: expected cpu, gpu or gpu:N \(N from 0\), got 'tpu'$"):
        holoray.render(scene, holoray.LensArray(lenses=(4, 4)), device="tpu")


def moving_shot(tmp_path):
    """primitives.nff sliding and turning over 3 frames of a 16x16-lens EIA."""
    (tmp_path / "s.nff").write_text((REPO / "examples" / "primitives.nff").read_text())
    shot = tmp_path / "shot.toml"
    shot.write_text('frames = 3\n[array]\nlenses = [16, 16]\npixels_per_lens = 6\n[[object]]\nscene = "s.nff"\n'
                    '[[object.key]]\nframe = 0\ntranslate = [0, 0, 0]\n'
                    '[[object.key]]\nframe = 2\ntranslate = [0.3, 0.1, 0]\nrotate = [0, 20, 0]\n')
    return shot


def test_animate_on_the_gpu_gives_the_cpu_frames(tmp_path):
    shot = moving_shot(tmp_path)
    cpu = [colour for _, colour, _ in holoray.animate(shot, method="full")]
    gpu = [colour for _, colour, _ in holoray.animate(shot, device="gpu")]
    assert len(gpu) == len(cpu) == 3
    for a, b in zip(cpu, gpu):
        assert psnr_8bit(a, b) >= 50
    assert psnr_8bit(gpu[0], gpu[2]) < 30  # the object moved on the GPU too


def test_animate_on_the_gpu_refuses_reuse_saying_why(tmp_path):
    with pytest.raises(ValueError, match=r"^reuse: goes with device cpu \(the GPU path traces every frame in full"):
        list(holoray.animate(moving_shot(tmp_path), device="gpu", reuse="color"))


def test_gpu_devices_lists_the_device_gpu_renders_on():
    devices = holoray.gpu_devices()
    assert devices and devices[0].startswith("0: ")
    scene = holoray.load_scene(str(REPO / "examples" / "primitives.nff"))
    name = holoray.render(scene, holoray.LensArray(lenses=(4, 4)), device="gpu:0").stats["device"]
    assert devices[0].startswith("0: " + name[:name.rfind(" (Vulkan")])


def test_released_devices_are_freed_once_and_the_next_render_makes_its_own():
    holoray.release_gpu_devices()  # what earlier tests of this process kept
    scene = holoray.load_scene(str(REPO / "examples" / "primitives.nff"))
    camera = holoray.LensArray(lenses=(12, 12), pixels_per_lens=6)
    first = holoray.render(scene, camera, device="gpu")
    assert holoray.release_gpu_devices() == 1
    assert holoray.release_gpu_devices() == 0
    again = holoray.render(scene, camera, device="gpu")
    assert np.array_equal(first.colour, again.colour)
    assert holoray.release_gpu_devices() == 1
