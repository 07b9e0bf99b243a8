"""holoray: integral images (elemental image arrays) from Python, numpy in and numpy out.

    import holoray
    scene = holoray.load_scene("examples/primitives.nff")
    eia = holoray.render(scene, holoray.LensArray(lenses=(64, 64), pixels_per_lens=8)).colour
    lf = holoray.light_field(eia, 8)        # (8, 8, 64, 64, 3): lf[v, u] is a sub-aperture view

Shapes, units and frames are in each function's docstring and in
__init__.pyi; the guide is docs/guide/python.md.
"""
from __future__ import annotations

import os

import numpy as np

from ._holoray import (  # noqa: F401
    Display,
    LensArray,
    LookingGlass,
    Pinhole,
    Quilt,
    Result,
    Scene,
    SceneError,
    World,
    __version__,
    gpu_devices,
    psnr,
    release_gpu_devices,
    render,
    subaperture_view,
)
from . import _holoray

__all__ = [
    "Display", "LensArray", "LookingGlass", "Pinhole", "Quilt", "Result", "Scene", "SceneError", "World",
    "animate", "gpu_devices", "interlace_quilt", "light_field", "load_scene", "psnr", "read_image",
    "release_gpu_devices", "render", "simulate_view",
    "subaperture_view", "write_image", "write_web",
]


def load_scene(path, *, camera_name="", texture_path=()):
    """NFF (.nff), Tachyon (.dat) or a mesh file through assimp (.obj, .gltf, .glb,
    .ply, .stl, .3ds, .dae, .fbx, .blend, .ac, ...). camera_name picks the mesh
    file's camera the viewpoint is (default: its first; ValueError naming the
    file's cameras when it has none of that name). texture_path: folders (a
    path or a sequence of them) where a texture the file names but that does
    not exist is looked for by its base name, after the file's own folder.
    Raises SceneError (file:line:col) for malformed input, OSError for a file
    that cannot be read (FileNotFoundError, PermissionError, IsADirectoryError)."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(2, "no such scene file", path)
    if isinstance(texture_path, (str, os.PathLike)):
        texture_path = [texture_path]
    return _holoray.load_scene(path, camera_name=camera_name, texture_path=[os.fspath(p) for p in texture_path])


def simulate_view(panel, display, eye=(0.0, 0.0, 600.0), width=800, samples=3):
    """What an eye at `eye` (mm, the display's frame, z > 0 in front) sees of
    `panel` (the display's native image, (H, W, 3) or (H, W)) through the lens
    sheet of the display file `display` (docs/display-files.md), as `holoray
    simulate`: float32 (h, width, 3), samples x samples per pixel. SceneError
    for a malformed display file, ValueError for a panel of another size."""
    return _holoray.simulate_view(panel, os.fspath(display), eye, width, samples)


def interlace_quilt(quilt, columns, rows, calibration):
    """A Looking Glass's native panel image (float32 (H, W, 3)) from a quilt of
    columns x rows views (view 0 bottom left) and the device's calibration
    file (visual.json), as `holoray interlace`. ValueError when the quilt is
    not columns x rows views of whole pixels; SceneError for a malformed
    calibration."""
    return _holoray.interlace_quilt(quilt, columns, rows, os.fspath(calibration))


def write_web(result, dir, *, name="holoray", encoding=None, pixels_per_lens=None, grid="square", quilt=None,
              looking_glass=None):
    """Writes the light-field page of `result` into the folder `dir`, as
    `holoray web`: a Result rendered through a LensArray (an EIA of any grid)
    or a Quilt, or an image array with pixels_per_lens (and grid) or
    quilt=(columns, rows). Open it with `holoray web --serve DIR`
    (docs/guide/web.md). encoding: 'linear' or 'srgb', how the values become
    the page's 8-bit codes (default: a Result's scene's, as `holoray render`
    writes it; 'srgb' for an array). looking_glass: a Looking Glass's
    calibration (visual.json) for a quilt's Looking Glass window. ValueError
    for another camera or an image that is not whole lenses or views."""
    return _holoray.write_web(result, os.fspath(dir), name=name, encoding=encoding, pixels_per_lens=pixels_per_lens,
                              grid=grid, quilt=quilt,
                              looking_glass=None if looking_glass is None else os.fspath(looking_glass))


def read_image(path):
    """PNG (8/16-bit), OpenEXR, JPEG, PPM/PGM, Targa, BMP, Radiance HDR as
    float32 (H, W, C), values as stored (8-bit codes / 255, EXR floats), row 0
    at the top; not copied on the way out. FileNotFoundError for a missing file."""
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise FileNotFoundError(2, "no such image file", path)
    return _holoray.read_image(path)


def write_image(path, array, encoding="linear"):
    """Writes an (H, W) or (H, W, C) array, C 1 to 4: .png (8-bit codes,
    encoding 'linear' or 'srgb'; uint8 arrays are codes already) or .exr
    (float32, linear). Written to a temporary name in the folder and renamed:
    a failed write leaves nothing. ValueError for another extension."""
    path = os.fspath(path)
    if os.path.splitext(path)[1].lower() not in (".png", ".exr"):
        raise ValueError(f"path: expected a .png or .exr file name, got {path!r}")
    _holoray.write_image(path, array, encoding)


def light_field(eia, pixels_per_lens):
    """The 4D light field of a square-grid EIA: (H, W, C) or (H, W) ->
    (P, P, Ny, Nx, C), angular axes first (v, u, then y, x), as plenpy and the
    HCI toolboxes hold light fields. lf[v, u] is sub-aperture view (u, v): pixel
    (u, v) of every elemental image, what `holoray subaperture --u u --v v` writes.
    A view of `eia` where it is an array (no copy)."""
    a = np.asarray(eia)
    p = int(pixels_per_lens)
    if p != pixels_per_lens or p < 1:
        raise ValueError(f"pixels_per_lens: expected a whole number >= 1, got {pixels_per_lens!r}")
    if a.ndim == 2:
        a = a[:, :, None]
    if a.ndim != 3:
        raise ValueError(f"eia: expected an image (H, W) or (H, W, C), got shape {a.shape}")
    h, w, c = a.shape
    if h % p or w % p or h == 0 or w == 0:
        raise ValueError(f"eia: a square grid of {p} px per lens needs a size that is a multiple of {p}, got {w}x{h}")
    return a.reshape(h // p, p, w // p, p, c).transpose(1, 3, 0, 2, 4)


def animate(shot_path, *, output=None, **options):
    """Renders a shot (docs/shot-format.md) frame by frame, with the keyframe
    reuse of `holoray animate`: yields (frame index, colour float32 (H, W, 3)
    linear, report row dict). Options are the CLI's, underscored: method,
    keyframe_interval (int or 'auto'), keyframe_motion, max_keyframe_interval,
    reuse, fill, rebuild_above, reach, leak_check, threads, camera (Pinhole,
    Display or LookingGlass), report (also trace in full: row['psnr']), cache,
    encoding, frames ('A:B', N or (a, b)), device ('cpu', 'gpu' or 'gpu:N':
    every frame traced in full on that device), camera_name and texture_path (as
    load_scene's: they replace and extend the shot file's), and render()'s light:
    integrator ('whitted' or 'path': every frame path traced in full),
    environment, environment_strength, environment_rotation, blender_principled,
    seed (every frame's) and animated_seed (True: seed + the frame's number, so
    that each frame's noise is its own). output: a folder the frames are
    also written to, as the CLI names them (frame_NNNN.png). The render runs
    on its own thread, a frame or two ahead; Ctrl-C or leaving the loop stops it."""
    shot_path = os.fspath(shot_path)
    if not os.path.isfile(shot_path):
        raise FileNotFoundError(2, "no such shot file", shot_path)
    frames = _holoray._Animation(shot_path, options)
    if output is not None:
        output = os.fspath(output)
        os.makedirs(output, exist_ok=True)
    digits = max(4, len(str(frames.frame_count - 1)))
    try:
        for index, colour, row in frames:
            if output is not None:
                write_image(os.path.join(output, f"frame_{index:0{digits}d}.png"), colour, frames.encoding)
            yield index, colour, row
    finally:
        frames.close()
