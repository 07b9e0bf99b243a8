"""holoray: integral images (elemental image arrays) from Python, numpy in and numpy out.

Frames: every coordinate passed in is in the scene's world frame and units.
Images are float32, linear, row 0 at the top, shaped (H, W, C).
"""
from __future__ import annotations

import os
from typing import Callable, Iterator, Literal, Mapping, Sequence

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
PathLike = str | os.PathLike[str]

class SceneError(ValueError):
    """A malformed scene, shot, display or calibration file: str(e) is
    'file:line:col: error: what was expected', the offending line and a caret."""
    file: str
    line: int
    column: int

class Scene:
    """A scene: loaded from a file (load_scene) or built in code. Units and frame: the world's."""
    def __init__(self) -> None: ...
    def add_mesh(self, vertices: ArrayLike, faces: ArrayLike, *, normals: ArrayLike | None = None,
                 uv: ArrayLike | None = None, colour: Sequence[float] = (0.8, 0.8, 0.8),
                 texture: ArrayLike | None = None) -> int:
        """Adds a triangle mesh; returns its object id (the 'id' AOV).

        vertices (N, 3) float, world units; faces (M, 3) integer indices into
        vertices, counter-clockwise seen from the front; normals (N, 3) float
        (per vertex, else flat shading); uv (N, 2) float, v up from the
        texture's bottom row; colour linear RGB; texture (H, W, 3|4) float
        (linear, 0..1) or uint8 (sRGB codes), multiplied by colour.
        Raises ValueError/TypeError naming the argument."""
    def add_sphere(self, centre: Sequence[float], radius: float, *,
                   colour: Sequence[float] = (0.8, 0.8, 0.8)) -> int:
        """Adds an exact sphere (world units); returns its object id."""
    def add_light(self, position: Sequence[float], colour: Sequence[float] = (1.0, 1.0, 1.0)) -> None:
        """Adds a point light, no falloff; colour is its radiance on a white
        surface facing it (docs/lights.md). A scene without lights gets a
        headlight at the viewpoint, as mesh files do."""
    def add_lights(self, path: str) -> None:
        """Adds the lights of a lights file (docs/lights.md, "Lights file"):
        point, spot, sun and area lights in Blender's words and units, in the
        scene's frame. SceneError at file:line:col for a malformed file."""
    def set_viewpoint(self, eye: Sequence[float], at: Sequence[float], up: Sequence[float],
                      fov_deg: float) -> None:
        """The viewpoint that places every camera, as NFF's 'v' (fov: vertical, degrees)."""
    @property
    def object_count(self) -> int: ...
    @property
    def light_count(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...

def load_scene(path: PathLike) -> Scene:
    """NFF, Tachyon (.dat) or a mesh file through assimp (OBJ, glTF, PLY, ...).
    Raises SceneError (file:line:col), FileNotFoundError."""

class LensArray:
    """The integral camera (docs/camera-model.md), placed by the scene's viewpoint
    as `holoray render` places it. lenses (x, y) or N; EIA size: lenses x
    pixels_per_lens (square grid; lenticular: x only, rows tall). grid
    'square', 'hex' or 'lenticular'; mode 'orthoscopic' or 'pseudoscopic';
    fov_lens in degrees (default 20) or gap, pitch, in scene units.
    origin, normal, up (world, all three, with pitch): an explicit placement
    instead of the viewpoint's."""
    def __init__(self, lenses: tuple[int, int] | int = (64, 64), pixels_per_lens: int = 8, grid: str = "square",
                 fov_lens: float | None = None, mode: str = "orthoscopic", *, pitch: float | None = None,
                 gap: float | None = None, rows: int | None = None, view_distance: float | None = None,
                 origin: Sequence[float] | None = None, normal: Sequence[float] | None = None,
                 up: Sequence[float] | None = None) -> None: ...
    @property
    def lenses(self) -> tuple[int, int]: ...
    @property
    def pixels_per_lens(self) -> int: ...

class Pinhole:
    """The viewpoint's ordinary perspective view; resolution (width, height),
    None: the scene's, else 512x512."""
    def __init__(self, resolution: tuple[int, int] | None = None, *, shift: tuple[float, float] = (0.0, 0.0)) -> None:
        """shift: lens shift, the window moved right and up by these fractions
        of its larger side (as a Blender camera's shift_x, shift_y)."""

class Quilt:
    """A Looking Glass quilt of columns x rows sheared views (view 0 bottom left)."""
    def __init__(self, columns: int, rows: int, view_resolution: tuple[int, int] = (420, 560),
                 view_cone: float = 40.0, *, focus_distance: float | None = None) -> None:
        """focus_distance: the views' focal (zero-parallax) plane's distance
        from the viewpoint (scene units); None: the viewpoint's |eye - at|."""

class Display:
    """A physical panel described by a display file (docs/display-files.md).
    FileNotFoundError for a missing file; SceneError (at render) for a bad one."""
    def __init__(self, path: PathLike) -> None: ...

class LookingGlass:
    """A Looking Glass's native panel image from its calibration (visual.json).
    FileNotFoundError for a missing file; SceneError (at render) for a bad one."""
    def __init__(self, path: PathLike, views: int = 48, *, focus_distance: float | None = None) -> None: ...

Camera = LensArray | Pinhole | Quilt | Display | LookingGlass

class Result:
    colour: np.ndarray
    """float32 (H, W, 3), linear RGB."""
    aovs: Mapping[str, np.ndarray]
    """'albedo' float32 (H, W, 3); 'depth' float32 (H, W), the camera's line
    parameter t, NaN for background; 'normal' float32 (H, W, 3), world frame,
    facing the viewer; 'id' int32 (H, W), object id, -1 for background."""
    stats: Mapping[str, Mapping[str, int | float] | str]
    """{'rays': {'eye', 'shadow', 'reflected', 'refracted', 'shadow_cached',
        'cache_samples', 'total'} (int), 'seconds': {'build', 'trace'} (float),
        'device': 'cpu' or the GPU's name}"""
    description: str
    """What was rendered, as `holoray render` prints it."""
    camera: LensArray | Pinhole | Quilt | Display | LookingGlass
    """The camera it was rendered through."""

class World:
    """A scene built once for many cameras and either device (OSPRay's World):
    render(world, camera) takes it in place of the scene and gives, bit for
    bit, what render(scene, camera) gives. Its light options are fixed here;
    render()'s, left at their defaults, take them, and one given otherwise
    raises ValueError naming it."""
    def __init__(self, scene: Scene, *, max_depth: int | None = None, integrator: str = "whitted",
                 environment: str | Sequence[float] | None = None, environment_strength: float = 1.0,
                 environment_rotation: float = 0.0, blender_principled: bool = False) -> None: ...
    @property
    def build_seconds(self) -> float: ...
    @property
    def skipped_polygons(self) -> int: ...

def render(scene: Scene | World, camera: Camera, *, threads: int | None = None, spp: int = 1,
           max_depth: int | None = None, aovs: Sequence[str] = (),
           progress: Callable[[float], object] | None = None, device: str = "cpu",
           integrator: str = "whitted", environment: str | Sequence[float] | None = None,
           environment_strength: float = 1.0, environment_rotation: float = 0.0,
           blender_principled: bool = False, share_views: int = 0) -> Result:
    """Renders scene through camera. Releases the GIL; Ctrl-C raises
    KeyboardInterrupt within half a second; progress(fraction) is called on
    the calling thread. device: 'cpu', 'gpu' (the first Vulkan GPU, else
    lavapipe) or 'gpu:N'; stats['device'] names it. integrator: 'whitted'
    (the paper's) or 'path' (path tracing, CPU; docs/lights.md). With
    'path': environment, an equirectangular .hdr/.exr file or a linear
    colour (r, g, b) (default: the scene's background colour), times
    environment_strength, turned by environment_rotation degrees about the
    scene's up axis as a Blender Mapping node turns it; blender_principled
    shades glTF materials as Blender 3.x's Principled BSDF; share_views
    (a Quilt, path traced on the CPU): each view also takes the samples of
    this many views on each side that see the same surface (0 to 16;
    docs/guide/light.md). Raises ValueError naming the argument, SceneError."""

def gpu_devices() -> list[str]:
    """The machine's Vulkan devices ('0: llvmpipe (...), CPU, Vulkan 1.3, 2.0
    GiB'), in the order 'gpu:N' counts them. RuntimeError saying what to
    install when there is no loader or device."""

def release_gpu_devices() -> int:
    """Frees the GPU devices this process keeps idle between renders (and
    their compiled kernels), handing their memory back to the driver; the
    next GPU render makes its own again (about a second). Returns how many
    were freed."""

def light_field(eia: ArrayLike, pixels_per_lens: int) -> np.ndarray:
    """(H, W, C) or (H, W) square-grid EIA -> (P, P, Ny, Nx, C) view (C = 1
    for (H, W)): lf[v, u] is sub-aperture view (u, v), as `holoray
    subaperture --u u --v v`. Not a copy. ValueError when H or W is not a
    multiple of P."""

def subaperture_view(eia: ArrayLike, pixels_per_lens: int, grid: str = "square", u: int = -1,
                     v: int = -1) -> np.ndarray:
    """Pixel (u, v) of every elemental image of an EIA (-1: P/2), as `holoray
    subaperture`: float32 (Ny, Nx, C) for square and hex grids, (H, Nx, C)
    for lenticular. grid: 'square', 'hex' or 'lenticular'. ValueError naming
    pixels_per_lens when the EIA is not whole lenses, or (u, v) outside."""

def simulate_view(panel: ArrayLike, display: PathLike, eye: ArrayLike = (0.0, 0.0, 600.0),
                  width: int = 800, samples: int = 3) -> np.ndarray:
    """What an eye at `eye` (mm, the display's frame, z > 0 in front) sees of
    the panel image through the display file's lens sheet, as `holoray
    simulate`: float32 (h, width, 3). SceneError for a malformed display
    file, ValueError for a panel of another size."""

def interlace_quilt(quilt: ArrayLike, columns: int, rows: int, calibration: PathLike) -> np.ndarray:
    """A Looking Glass's native panel image, float32 (H, W, 3), from a quilt of
    columns x rows views and the device's calibration (visual.json), as
    `holoray interlace`. ValueError when the quilt is not whole views."""

def write_web(result: Result | ArrayLike, dir: PathLike, *, name: str = "holoray",
              encoding: Literal["linear", "srgb"] | None = None, pixels_per_lens: int | None = None,
              grid: Literal["square", "hex", "lenticular"] = "square", quilt: tuple[int, int] | None = None,
              looking_glass: PathLike | None = None) -> None:
    """Writes the light-field page of a Result (an EIA or a quilt) or an image
    array (with pixels_per_lens, or quilt=(columns, rows)) into dir, as
    `holoray web`; open it with `holoray web --serve DIR`."""

def animate(shot_path: PathLike, *, output: PathLike | None = None, **options: object
            ) -> Iterator[tuple[int, np.ndarray, dict[str, object]]]:
    """Renders a shot (docs/shot-format.md) frame by frame with keyframe reuse:
    yields (frame index, colour (H, W, 3) float32, report row). Options as
    `holoray animate`'s, underscored: method ('full', 'reproject', 'reverse'),
    keyframe_interval (int or 'auto'), keyframe_motion, max_keyframe_interval,
    reuse, fill, rebuild_above, reach, leak_check, threads, camera (Pinhole,
    Display or LookingGlass), report (bool: also trace in full, row['psnr']),
    cache (bool), encoding, frames ('A:B', N or (a, b)), device ('cpu', 'gpu'
    or 'gpu:N': every frame traced in full there). The row: frame,
    keyframe, seconds, reference_seconds, pixels, reprojected, missed, leaks,
    rejected, traced, interpolated, rays, psnr, hold_psnr, copied_from,
    rebuilt. output: a folder the frames are also written to, as the CLI
    names them (frame_NNNN.png). TypeError for an unknown option."""

def read_image(path: PathLike) -> np.ndarray:
    """PNG, EXR, JPEG, ... as float32 (H, W, C), values as stored (8-bit codes / 255).
    FileNotFoundError for a missing file, RuntimeError for an unreadable one."""

def write_image(path: PathLike, array: ArrayLike, encoding: str = "linear") -> None:
    """.png (8-bit; encoding 'linear' or 'srgb'; uint8 arrays are codes) or .exr
    (float); written to a temporary name and renamed. ValueError for another
    extension or shape."""

def psnr(a: ArrayLike, b: ArrayLike) -> float:
    """PSNR in dB of two images of values in 0..1 nominal (8-bit scale, as
    `holoray compare`); inf when equal."""
