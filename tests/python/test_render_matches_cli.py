"""holoray.render gives the floats `holoray render ... -o out.exr` writes.

Each case renders examples/primitives.nff through one camera with the
module and with the CLI (same options, same thread count); the CLI's EXR is
read back with holoray.read_image and the two must be equal sample for
sample (EXR keeps float32 exactly, so no tolerance is needed). The ray
counts and the description are compared with what the CLI prints.
"""
from __future__ import annotations

import json
import pathlib
import re

import numpy as np
import pytest

import holoray
from conftest import REPO, THREADS
from helpers import normalise_spaces, parse_rays, plane, read_image

EXAMPLE_CALIBRATION = REPO / "examples" / "displays" / "looking_glass_example_calibration.json"

# A slanted lenticular sheet with RGB subpixels (the display camera proper:
# not whole pixels per lens), 96x64 pixels.
SLANTED_DISPLAY = """\
name = "small slanted lenticular (test)"
[panel]
resolution = [96, 64]
pixel_pitch_mm = 0.1
subpixels = "rgb"
[lens]
grid = "lenticular"
pitch_mm = 0.44
slant_deg = 9.4623
focal_length_mm = 1.2
"""

# Whole pixels per lens, no subpixels: rendered through the integral camera.
SQUARE_DISPLAY = """\
[panel]
resolution = [64, 48]
pixel_pitch_mm = 0.1
subpixels = "none"
[lens]
grid = "square"
pitch_mm = 0.4
focal_length_mm = 1.0
"""

# A hex array under a BGR panel, pseudoscopic, a fixed scale and depth.
HEX_DISPLAY = """\
[panel]
resolution = [80, 60]
pixel_pitch_mm = 0.1
subpixels = "bgr"
[lens]
grid = "hex"
pitch_mm = 0.53
gap_mm = 1.1
offset_mm = 0.07
[scene]
mode = "pseudoscopic"
units_per_mm = 0.5
depth = 0.3
"""


@pytest.fixture(scope="session")
def device_files(tmp_path_factory) -> dict:
    """Small display files and a small Looking Glass calibration, in a session folder."""
    d = tmp_path_factory.mktemp("devices")
    files = {}
    for name, text in (("slanted.toml", SLANTED_DISPLAY), ("square.toml", SQUARE_DISPLAY), ("hex.toml", HEX_DISPLAY)):
        (d / name).write_text(text)
        files[name] = d / name
    # The example calibration (1536x2048) shrunk to a 96x128 panel: same
    # pitch, slope and centre, so the same mapping on fewer pixels.
    cal = json.loads(EXAMPLE_CALIBRATION.read_text())
    cal["screenW"]["value"] = 96.0
    cal["screenH"]["value"] = 128.0
    (d / "lg_small.json").write_text(json.dumps(cal))
    files["lg_small.json"] = d / "lg_small.json"
    return files


def _case(cli_args, camera, **render_kwargs):
    return cli_args, camera, render_kwargs


# name -> function(device_files) -> (CLI arguments, camera, render keyword arguments)
CASES = {
    "square": lambda f: _case(["--lenses", "16x16", "--pixels-per-lens", "4"],
                              holoray.LensArray(lenses=(16, 16), pixels_per_lens=4)),
    "square_rectangular_fov_pseudoscopic": lambda f: _case(
        ["--lenses", "12x10", "--pixels-per-lens", "5", "--fov-lens", "30", "--mode", "pseudoscopic"],
        holoray.LensArray(lenses=(12, 10), pixels_per_lens=5, fov_lens=30, mode="pseudoscopic")),
    "square_pitch_gap": lambda f: _case(
        ["--lenses", "16x12", "--pixels-per-lens", "4", "--pitch", "0.5", "--gap", "1.5"],
        holoray.LensArray(lenses=(16, 12), pixels_per_lens=4, pitch=0.5, gap=1.5)),
    "square_spp3_max_depth2": lambda f: _case(
        ["--lenses", "16x16", "--pixels-per-lens", "4", "--spp", "3", "--max-depth", "2"],
        holoray.LensArray(lenses=(16, 16), pixels_per_lens=4), spp=3, max_depth=2),
    "hex": lambda f: _case(["--grid", "hex", "--lenses", "16x16", "--pixels-per-lens", "4"],
                           holoray.LensArray(lenses=(16, 16), pixels_per_lens=4, grid="hex")),
    "hex_rows": lambda f: _case(["--grid", "hex", "--lenses", "15x13", "--pixels-per-lens", "5", "--rows", "50"],
                                holoray.LensArray(lenses=(15, 13), pixels_per_lens=5, grid="hex", rows=50)),
    "lenticular": lambda f: _case(["--grid", "lenticular", "--lenses", "24x24", "--pixels-per-lens", "4", "--rows", "48"],
                                  holoray.LensArray(lenses=(24, 24), pixels_per_lens=4, grid="lenticular", rows=48)),
    "pinhole": lambda f: _case(["--camera", "pinhole", "--resolution", "48x32"],
                               holoray.Pinhole(resolution=(48, 32))),
    "pinhole_scene_resolution": lambda f: _case(["--camera", "pinhole"], holoray.Pinhole()),
    "quilt": lambda f: _case(["--quilt", "3x2", "--resolution", "24x32", "--view-cone", "40"],
                             holoray.Quilt(3, 2, view_resolution=(24, 32), view_cone=40.0)),
    "quilt_cone25": lambda f: _case(["--quilt", "4x3", "--resolution", "20x16", "--view-cone", "25"],
                                    holoray.Quilt(4, 3, view_resolution=(20, 16), view_cone=25.0)),
    "quilt_path_shared_views": lambda f: _case(
        ["--quilt", "4x2", "--resolution", "20x16", "--integrator", "path", "--spp", "2", "--share-views", "2"],
        holoray.Quilt(4, 2, view_resolution=(20, 16)), integrator="path", spp=2, share_views=2),
    "pinhole_path_seed": lambda f: _case(
        ["--camera", "pinhole", "--resolution", "48x32", "--integrator", "path", "--spp", "2", "--seed", "9"],
        holoray.Pinhole(resolution=(48, 32)), integrator="path", spp=2, seed=9),
    "display_slanted_rgb": lambda f: _case(["--display", f["slanted.toml"]], holoray.Display(f["slanted.toml"])),
    "display_whole_pixels_square": lambda f: _case(["--display", f["square.toml"]], holoray.Display(f["square.toml"])),
    "display_hex_bgr_pseudoscopic": lambda f: _case(["--display", f["hex.toml"]], holoray.Display(str(f["hex.toml"]))),
    "looking_glass_small": lambda f: _case(["--looking-glass", f["lg_small.json"]],
                                           holoray.LookingGlass(f["lg_small.json"])),
    "looking_glass_small_24_views": lambda f: _case(["--looking-glass", f["lg_small.json"], "--views", "24"],
                                                    holoray.LookingGlass(f["lg_small.json"], views=24)),
}


def _cli_output(out_dir: pathlib.Path, stem: str) -> pathlib.Path:
    """The EXR the CLI wrote for -o out_dir/stem.exr: a quilt's name is stem_qsCxRaASPECT.exr."""
    exact = out_dir / f"{stem}.exr"
    if exact.exists():
        return exact
    pattern = re.compile(rf"^{re.escape(stem)}_qs\d+x\d+a[\d.]+\.exr$")
    found = [p for p in out_dir.iterdir() if pattern.match(p.name)]
    assert len(found) == 1, f"expected one {stem}.exr or quilt name in {sorted(p.name for p in out_dir.iterdir())}"
    return found[0]


@pytest.fixture(scope="module")
def rendered(tmp_path_factory, run_cli, primitives_path, primitives, device_files):
    """rendered(name) -> (CLI stdout, CLI colour, module Result), each case run once."""
    cache = {}
    out_dir = tmp_path_factory.mktemp("render_vs_cli")

    def get(name):
        if name not in cache:
            cli_args, camera, kwargs = CASES[name](device_files)
            out = out_dir / f"{name}.exr"
            proc = run_cli("render", primitives_path, *cli_args, "--threads", THREADS, "-o", out)
            cli_colour = read_image(_cli_output(out_dir, name))
            result = holoray.render(primitives, camera, threads=THREADS, **kwargs)
            cache[name] = (proc.stdout, cli_colour, result)
        return cache[name]

    return get


@pytest.mark.parametrize("name", list(CASES))
def test_colour_equals_cli_exr(rendered, name):
    _, cli_colour, result = rendered(name)
    colour = result.colour
    assert isinstance(colour, np.ndarray)
    assert colour.dtype == np.float32
    assert colour.ndim == 3 and colour.shape[2] == 3
    assert colour.shape == cli_colour.shape
    assert np.isfinite(colour).all()
    assert colour.max() > 0, "the render is black"
    np.testing.assert_array_equal(colour, cli_colour)


@pytest.mark.parametrize("name", list(CASES))
def test_ray_counts_equal_cli(rendered, name):
    stdout, _, result = rendered(name)
    cli_rays = parse_rays(stdout)
    rays = result.stats["rays"]
    for kind in ("eye", "shadow", "reflected", "refracted", "total"):
        assert int(rays[kind]) == cli_rays[kind], (kind, dict(rays), cli_rays)
    assert set(result.stats["seconds"]) >= {"build", "trace"}
    assert all(float(s) >= 0 for s in result.stats["seconds"].values())


@pytest.mark.parametrize("name", list(CASES))
def test_description_is_what_the_cli_prints(rendered, name):
    stdout, _, result = rendered(name)
    lines = normalise_spaces(result.description)
    assert lines, "empty description"
    cli_lines = normalise_spaces(stdout)
    for line in lines:
        assert any(line in cli_line for cli_line in cli_lines), \
            f"{line!r} is not among the CLI's lines:\n" + "\n".join(cli_lines)


def test_pinhole_default_resolution_is_the_scenes(rendered):
    # primitives.nff says 'resolution 512 512'.
    _, _, result = rendered("pinhole_scene_resolution")
    assert result.colour.shape == (512, 512, 3)


def test_lens_array_size_is_lenses_times_pixels_per_lens(rendered):
    assert rendered("square")[2].colour.shape == (64, 64, 3)
    assert rendered("square_rectangular_fov_pseudoscopic")[2].colour.shape == (50, 60, 3)
    assert rendered("lenticular")[2].colour.shape == (48, 96, 3)
    assert rendered("hex_rows")[2].colour.shape == (50, 75, 3)


def test_quilt_size_is_columns_by_rows_of_views(rendered):
    assert rendered("quilt")[2].colour.shape == (2 * 32, 3 * 24, 3)
    assert rendered("quilt_cone25")[2].colour.shape == (3 * 16, 4 * 20, 3)


def test_looking_glass_example_calibration_equals_cli(tmp, run_cli, primitives_path, primitives):
    """The shipped calibration as it is: a 1536x2048 panel (about 3 s a side on 2 cores)."""
    out = tmp / "lg.exr"
    run_cli("render", primitives_path, "--looking-glass", EXAMPLE_CALIBRATION, "--threads", THREADS, "-o", out)
    result = holoray.render(primitives, holoray.LookingGlass(EXAMPLE_CALIBRATION), threads=THREADS)
    assert result.colour.shape == (2048, 1536, 3)
    np.testing.assert_array_equal(result.colour, read_image(out))


AOV_CASES = {
    "square": (["--lenses", "16x16", "--pixels-per-lens", "4"], lambda: holoray.LensArray(lenses=(16, 16), pixels_per_lens=4)),
    "hex": (["--grid", "hex", "--lenses", "16x16", "--pixels-per-lens", "4"],
            lambda: holoray.LensArray(lenses=(16, 16), pixels_per_lens=4, grid="hex")),
    "lenticular": (["--grid", "lenticular", "--lenses", "24x24", "--pixels-per-lens", "4", "--rows", "48"],
                   lambda: holoray.LensArray(lenses=(24, 24), pixels_per_lens=4, grid="lenticular", rows=48)),
    "pseudoscopic": (["--lenses", "16x16", "--pixels-per-lens", "4", "--mode", "pseudoscopic"],
                     lambda: holoray.LensArray(lenses=(16, 16), pixels_per_lens=4, mode="pseudoscopic")),
    "pinhole": (["--camera", "pinhole", "--resolution", "48x32"], lambda: holoray.Pinhole(resolution=(48, 32))),
    "quilt": (["--quilt", "3x2", "--resolution", "24x32"], lambda: holoray.Quilt(3, 2, view_resolution=(24, 32))),
}


@pytest.mark.parametrize("name", list(AOV_CASES))
def test_aovs_equal_cli_aov_files(tmp, run_cli, primitives_path, primitives, name):
    cli_args, camera = AOV_CASES[name]
    run_cli("render", primitives_path, *cli_args, "--aov", "albedo,depth,normal,id", "--threads", THREADS,
            "-o", tmp / "eia.exr")
    # AOVs are written beside the image as <stem>.<aov>.exr (docs/guide/stills.md);
    # a quilt's stem is eia_qsCxRaASPECT.
    colour_file = _cli_output(tmp, "eia")
    stem = colour_file.name[: -len(".exr")]
    cli = {aov: read_image(tmp / f"{stem}.{aov}.exr") for aov in ("albedo", "depth", "normal", "id")}

    result = holoray.render(primitives, camera(), threads=THREADS, aovs=("albedo", "depth", "normal", "id"))
    np.testing.assert_array_equal(result.colour, read_image(colour_file))
    aovs = result.aovs
    assert set(aovs) == {"albedo", "depth", "normal", "id"}
    h, w = result.colour.shape[:2]

    assert aovs["albedo"].dtype == np.float32 and aovs["albedo"].shape == (h, w, 3)
    np.testing.assert_array_equal(aovs["albedo"], cli["albedo"])

    assert aovs["normal"].dtype == np.float32 and aovs["normal"].shape == (h, w, 3)
    np.testing.assert_array_equal(aovs["normal"], cli["normal"])

    depth = aovs["depth"]
    assert depth.dtype == np.float32 and depth.shape == (h, w)
    np.testing.assert_array_equal(depth, plane(cli["depth"]))  # NaN (background) equals NaN
    assert np.isfinite(depth).any(), "no surface seen"

    ids = aovs["id"]
    assert ids.dtype == np.int32 and ids.shape == (h, w)
    cli_id = plane(cli["id"])
    assert np.array_equal(cli_id, np.round(cli_id)), "the CLI's id EXR holds whole numbers"
    np.testing.assert_array_equal(ids.astype(np.int64), cli_id.astype(np.int64))

    # Background is the same pixels in every AOV.
    background = ids == -1
    np.testing.assert_array_equal(background, np.isnan(depth))
    assert (aovs["normal"][background] == 0).all()


def test_only_the_requested_aovs_are_returned(primitives):
    camera = holoray.LensArray(lenses=(8, 8), pixels_per_lens=4)
    assert len(holoray.render(primitives, camera, threads=THREADS).aovs) == 0
    result = holoray.render(primitives, camera, threads=THREADS, aovs=["depth"])
    assert set(result.aovs) == {"depth"}


def test_aovs_do_not_change_the_colour(primitives):
    camera = holoray.LensArray(lenses=(16, 16), pixels_per_lens=4)
    plain = holoray.render(primitives, camera, threads=THREADS)
    with_aovs = holoray.render(primitives, camera, threads=THREADS, aovs=("albedo", "depth", "normal", "id"))
    np.testing.assert_array_equal(plain.colour, with_aovs.colour)


def test_thread_count_does_not_change_the_image(primitives):
    camera = holoray.LensArray(lenses=(24, 20), pixels_per_lens=4)
    one = holoray.render(primitives, camera, threads=1, aovs=("depth",))
    two = holoray.render(primitives, camera, threads=2, aovs=("depth",))
    default = holoray.render(primitives, camera, aovs=("depth",))
    np.testing.assert_array_equal(one.colour, two.colour)
    np.testing.assert_array_equal(one.colour, default.colour)
    np.testing.assert_array_equal(one.aovs["depth"], two.aovs["depth"])


def test_rendering_a_scene_twice_gives_the_same_image(primitives):
    camera = holoray.Quilt(2, 2, view_resolution=(16, 16))
    np.testing.assert_array_equal(holoray.render(primitives, camera, threads=THREADS).colour,
                                  holoray.render(primitives, camera, threads=THREADS).colour)


def test_load_scene_counts_match_the_cli(run_cli, primitives_path, primitives, tmp):
    # The CLI prints 'scene  PATH: 394 objects, 2 lights'.
    proc = run_cli("render", primitives_path, "--lenses", "2x2", "--pixels-per-lens", "2", "-o", tmp / "x.exr")
    line = next(l for l in normalise_spaces(proc.stdout) if l.startswith("scene "))
    objects, lights = [int(tok) for tok in line.replace(",", " ").split() if tok.isdigit()][-2:]
    assert primitives.object_count == objects
    assert primitives.light_count == lights
