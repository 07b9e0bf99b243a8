"""Helpers shared by the Python module's tests (plain functions, no fixtures)."""
from __future__ import annotations

import os
import re

import numpy as np


def parse_rays(stdout: str) -> dict:
    """The CLI's 'rays  eye N, shadow N, reflected N, refracted N; total N' line."""
    m = re.search(r"^rays\s+eye (\d+), shadow (\d+), reflected (\d+), refracted (\d+); total (\d+)", stdout, re.M)
    assert m, f"no rays line in:\n{stdout}"
    return dict(zip(("eye", "shadow", "reflected", "refracted", "total"), map(int, m.groups())))


def plane(image: np.ndarray) -> np.ndarray:
    """A one-channel image as (H, W): read_image gives (H, W, 1) for the CLI's depth and id EXRs."""
    image = np.asarray(image)
    if image.ndim == 3 and image.shape[2] == 1:
        return image[:, :, 0]
    return image


def srgb_encode(linear: np.ndarray) -> np.ndarray:
    """IEC 61966-2-1, in float64, clamped to 0..1 first."""
    v = np.clip(np.asarray(linear, dtype=np.float64), 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)


def srgb_decode(encoded: np.ndarray) -> np.ndarray:
    c = np.asarray(encoded, dtype=np.float64)
    return np.where(c <= 0.04045, c / 12.92, np.power((c + 0.055) / 1.055, 2.4))


def png_codes(values: np.ndarray) -> np.ndarray:
    """The 8-bit codes `holoray` writes for (already encoded) values: floor(255 v + 0.5), clamped."""
    return np.clip(np.floor(255.0 * np.asarray(values, dtype=np.float64) + 0.5), 0, 255)


def vm_rss_bytes() -> int:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmRSS in /proc/self/status")


def normalise_spaces(text: str) -> list[str]:
    """Lines with runs of blanks collapsed, empty lines dropped."""
    return [" ".join(line.split()) for line in text.splitlines() if line.strip()]


def read_image(path):
    """holoray.read_image(str(path)): taking os.PathLike is tested once, in
    test_images.py, so that a failure there does not fail every comparison."""
    import holoray

    return holoray.read_image(os.fspath(path))


def write_image(path, array, *args, **kwargs):
    """holoray.write_image(str(path), ...): see read_image."""
    import holoray

    return holoray.write_image(os.fspath(path), array, *args, **kwargs)
