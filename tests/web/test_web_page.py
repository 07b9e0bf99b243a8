"""The light-field page (`holoray web`, src/web/page) in headless Chromium.

Each test writes a page with the CLI, serves it with `holoray web --serve`,
opens states of it through tests/web/capture.mjs (playwright-core driving
Debian's chromium, WebGL2 on SwiftShader) and holds what the page drew to
what the files say, computed here with numpy: a view is the EIA's pixels
(u, v) behind every lens, a view between views the bilinear blend of the
four around it, a refocused view the shift-and-add of the views, all
blended in linear light as the page blends them.

Run from the repository root (scripts/setup.sh installs chromium and
tests/web's node_modules):

    PYTHONPATH=build/python HOLORAY_CLI=build/holoray /usr/bin/python3 -m pytest tests/web -q
"""
from __future__ import annotations

import os
import pathlib
import re
import shutil
import subprocess

import numpy as np
import pytest

import holoray

HERE = pathlib.Path(__file__).resolve().parent
REPO = HERE.parents[1]
CLI = pathlib.Path(os.environ.get("HOLORAY_CLI", REPO / "build" / "holoray")).resolve()
PRIMITIVES = REPO / "examples" / "primitives.nff"


def psnr(a: np.ndarray, b: np.ndarray) -> float:
    """PSNR in dB of two images of values 0..1 (the 8-bit scale), RGB."""
    mse = float(np.mean((a[..., :3].astype(np.float64) - b[..., :3]) ** 2))
    return float("inf") if mse == 0 else 10 * np.log10(1 / mse)


def decode(codes: np.ndarray) -> np.ndarray:
    """sRGB codes (0..1) to linear light, as an SRGB8 texture reads them."""
    c = codes[..., :3].astype(np.float64)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def encode(linear: np.ndarray) -> np.ndarray:
    """Linear light to sRGB codes (0..1), rounded to 8 bits as a canvas holds them."""
    c = np.clip(linear, 0, 1)
    e = np.where(c <= 0.0031308, c * 12.92, 1.055 * c ** (1 / 2.4) - 0.055)
    return np.round(e * 255) / 255


def run(*args: object) -> str:
    done = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture(scope="module")
def browser_ready() -> None:
    """The page's test tools: node, Debian's chromium, playwright-core."""
    missing = [what for what, ok in [
        ("node", shutil.which("node")),
        ("chromium", pathlib.Path(os.environ.get("CHROMIUM", "/usr/bin/chromium")).exists()),
        ("playwright-core (tests/web/node_modules)", (HERE / "node_modules" / "playwright-core").is_dir()),
    ] if not ok]
    if missing:
        pytest.fail(f"missing {', '.join(missing)}: run scripts/setup.sh")


class Served:
    """`holoray web --serve DIR` on a free port, for the duration of a test."""

    def __init__(self, folder: pathlib.Path):
        self.process = subprocess.Popen([str(CLI), "web", "--serve", str(folder), "--port", "0"],
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        line = self.process.stdout.readline()
        match = re.search(r" at (http://\S+) ", line)
        if not match:
            self.process.kill()
            raise AssertionError(f"no address from --serve: {line!r} {self.process.stderr.read()}")
        self.url = match.group(1)

    def __enter__(self) -> "Served":
        return self

    def __exit__(self, *exc: object) -> None:
        self.process.terminate()
        self.process.wait(timeout=10)


def capture(folder: pathlib.Path, states: list[str], out: pathlib.Path,
            screenshot: pathlib.Path | None = None) -> list[np.ndarray | str]:
    """What the page in `folder` draws for each state (a fragment): an image
    of codes 0..1, or the message the page shows instead; with `screenshot`,
    the first state's page as a reader sees it, saved there."""
    out.mkdir(exist_ok=True)
    env = dict(os.environ, **({"SCREENSHOT": str(screenshot)} if screenshot else {}))
    with Served(folder) as server:
        done = subprocess.run(["node", str(HERE / "capture.mjs"), str(out), *[server.url + s for s in states]],
                              capture_output=True, text=True, timeout=300, env=env)
    assert done.returncode == 0, done.stderr
    shown: list[np.ndarray | str] = []
    for k in range(len(states)):
        error = out / f"{k}.error.txt"
        shown.append(error.read_text().strip() if error.exists() else holoray.read_image(str(out / f"{k}.png"))[..., :3])
    return shown


@pytest.fixture(scope="module")
def square(tmp_path_factory: pytest.TempPathFactory) -> tuple[pathlib.Path, np.ndarray, int]:
    """A square-grid EIA of primitives.nff (24x16 lenses of 6 px) and its page."""
    d = tmp_path_factory.mktemp("square")
    run("render", PRIMITIVES, "--lenses", "24x16", "--pixels-per-lens", 6, "-q", "--threads", 2, "-o", d / "eia.png")
    run("web", d / "eia.png", "--pixels-per-lens", 6, "-o", d / "page")
    return d, holoray.read_image(str(d / "eia.png"))[..., :3], 6


def view_of(eia: np.ndarray, p: int, u: int, v: int) -> np.ndarray:
    """Sub-aperture view (u, v) of a square EIA: pixel (u, v) of every lens."""
    return eia[v::p, u::p]


def test_each_view_is_the_eias_pixels_u_v_behind_every_lens(browser_ready, square, tmp_path):
    d, eia, p = square
    pairs = [(0, 0), (5, 5), (2, 3), (4, 1), (3, 3)]
    shown = capture(d / "page", [f"#u={u}&v={v}" for u, v in pairs] + [""], tmp_path)
    for (u, v), got in zip(pairs, shown):
        assert psnr(got, view_of(eia, p, u, v)) >= 45, (u, v)
    # No state in the address: the middle view, P / 2 as `holoray subaperture` takes it.
    assert psnr(shown[-1], view_of(eia, p, p // 2, p // 2)) >= 45


def test_a_view_between_views_is_the_bilinear_blend_of_the_four(browser_ready, square, tmp_path):
    d, eia, p = square
    points = [(2.5, 3.25), (0.75, 4.5), (4.2, 0.1)]
    shown = capture(d / "page", [f"#u={u}&v={v}" for u, v in points], tmp_path)
    for (u, v), got in zip(points, shown):
        u0, v0 = int(u), int(v)
        fu, fv = u - u0, v - v0
        lin = lambda a, b: decode(view_of(eia, p, a, b))  # noqa: E731
        blend = ((1 - fu) * (1 - fv) * lin(u0, v0) + fu * (1 - fv) * lin(u0 + 1, v0) + (1 - fu) * fv * lin(u0, v0 + 1)
                 + fu * fv * lin(u0 + 1, v0 + 1))
        assert psnr(got, encode(blend)) >= 40, (u, v)
        # and it is not simply the nearest view
        assert psnr(got, view_of(eia, p, round(u), round(v))) < psnr(got, encode(blend))


def shift_and_add(eia: np.ndarray, p: int, u: float, v: float, focus: float, aperture: float) -> np.ndarray:
    """The views within `aperture` views of (u, v), each shifted by focus x
    its offset (lenses; bilinear, edges repeated), averaged in linear light."""
    ny, nx = eia.shape[0] // p, eia.shape[1] // p
    ys, xs = np.mgrid[0:ny, 0:nx].astype(np.float64)
    total, n = np.zeros((ny, nx, 3)), 0
    for b in range(p):
        for a in range(p):
            du, dv = a - u, b - v
            if du * du + dv * dv > aperture * aperture:
                continue
            view = decode(view_of(eia, p, a, b))
            qx, qy = xs + focus * du, ys + focus * dv
            x0, y0 = np.floor(qx), np.floor(qy)
            wx, wy = (qx - x0)[..., None], (qy - y0)[..., None]
            at = lambda y, x: view[np.clip(y, 0, ny - 1).astype(int), np.clip(x, 0, nx - 1).astype(int)]  # noqa: E731
            total += ((1 - wy) * ((1 - wx) * at(y0, x0) + wx * at(y0, x0 + 1)) + wy * ((1 - wx) * at(y0 + 1, x0) + wx * at(y0 + 1, x0 + 1)))
            n += 1
    return encode(total / n)


def test_refocus_is_the_shift_and_add_of_the_views(browser_ready, square, tmp_path):
    d, eia, p = square
    cases = [(2.5, 2.5, 0.5, 2.0), (2.5, 2.5, -0.75, 3.0), (1.0, 4.0, 1.25, 1.5)]
    shown = capture(d / "page", [f"#u={u}&v={v}&focus={f}&aperture={r}" for u, v, f, r in cases], tmp_path)
    for (u, v, f, r), got in zip(cases, shown):
        want = shift_and_add(eia, p, u, v, f, r)
        assert psnr(got, want) >= 40, (u, v, f, r)
    # Focus moves the plane: two depths give two images.
    assert psnr(shown[0], shown[1]) < 40


def test_the_eia_and_the_grid_of_views_are_shown_whole(browser_ready, square, tmp_path):
    d, eia, p = square
    eia_shown, grid_shown = capture(d / "page", ["#show=eia", "#show=grid"], tmp_path)
    assert psnr(eia_shown, eia) >= 45
    ny, nx = eia.shape[0] // p, eia.shape[1] // p
    assert grid_shown.shape == eia.shape
    assert psnr(grid_shown[3 * ny:4 * ny, 2 * nx:3 * nx], view_of(eia, p, 2, 3)) >= 45  # tile column u, row v


def test_a_hexagonal_eias_views_are_holoray_subapertures(browser_ready, tmp_path):
    run("render", PRIMITIVES, "--grid", "hex", "--lenses", "20x14", "--pixels-per-lens", 7, "-q", "--threads", 2,
        "-o", tmp_path / "hex.png")
    run("web", tmp_path / "hex.png", "--grid", "hex", "--pixels-per-lens", 7, "-o", tmp_path / "page")
    def sub(u: int, v: int) -> np.ndarray:
        run("subaperture", tmp_path / "hex.png", "--grid", "hex", "--pixels-per-lens", 7, "--u", u, "--v", v,
            "-o", tmp_path / "sub.png")
        return holoray.read_image(str(tmp_path / "sub.png"))[..., :3]

    pairs = [(3, 3), (0, 6), (5, 2)]
    shown = capture(tmp_path / "page", [f"#u={u}&v={v}" for u, v in pairs] + ["#u=2.25&v=4.5"], tmp_path / "shots")
    for (u, v), got in zip(pairs, shown):
        assert psnr(got, sub(u, v)) >= 45, (u, v)
    # Between views: the bilinear blend of the four subapertures around (2.25, 4.5), in linear light.
    blend = (0.75 * 0.5 * decode(sub(2, 4)) + 0.25 * 0.5 * decode(sub(3, 4)) + 0.75 * 0.5 * decode(sub(2, 5))
             + 0.25 * 0.5 * decode(sub(3, 5)))
    assert psnr(shown[3], encode(blend)) >= 40


def test_a_quilts_views_run_left_to_right_from_the_bottom_left_tile(browser_ready, tmp_path):
    run("render", PRIMITIVES, "--quilt", "4x2", "--resolution", "32x24", "-q", "--threads", 2, "-o", tmp_path / "q.png")
    quilt_file = next(tmp_path.glob("q_qs4x2*.png"))
    run("web", quilt_file, "-o", tmp_path / "page")
    quilt = holoray.read_image(str(quilt_file))[..., :3]
    shown = capture(tmp_path / "page", [f"#u={n}" for n in range(8)], tmp_path / "shots")
    for n, got in enumerate(shown):
        col, row = n % 4, 1 - n // 4
        assert psnr(got, quilt[row * 24:(row + 1) * 24, col * 32:(col + 1) * 32]) >= 45, n


def test_a_malformed_or_missing_image_shows_a_message_not_a_blank_canvas(browser_ready, square, tmp_path):
    d, _, _ = square
    page = tmp_path / "page"
    shutil.copytree(d / "page", page)
    (page / "views.png").write_bytes(b"\x89PNG\r\n\x1a\n not a png")
    (malformed,) = capture(page, [""], tmp_path / "malformed")
    assert isinstance(malformed, str) and malformed.startswith("views.png: not an image this browser can decode"), malformed
    (page / "views.png").unlink()
    (missing,) = capture(page, [""], tmp_path / "missing")
    assert missing == "views.png: the server answered 404 Not Found", missing


def test_the_looking_glass_window_is_holoray_interlace_of_the_quilt(browser_ready, tmp_path):
    run("render", PRIMITIVES, "--quilt", "4x2", "--resolution", "48x64", "-q", "--threads", 2, "-o", tmp_path / "q.png")
    quilt_file = next(tmp_path.glob("q_qs4x2*.png"))
    example = REPO / "examples" / "displays" / "looking_glass_example_calibration.json"
    # The example, and the same with subpixel cells in a checkerboard (the
    # newer devices' calibrations).
    cells = example.read_text().rstrip().rstrip("}") + (
        ', "CellPatternMode": {"value": 1}, "subpixelCells": ['
        '{"ROffsetX": 0.0, "ROffsetY": 0.0, "GOffsetX": 0.333, "GOffsetY": 0.0, "BOffsetX": 0.667, "BOffsetY": 0.0},'
        '{"ROffsetX": 0.667, "ROffsetY": 0.0, "GOffsetX": 0.333, "GOffsetY": 0.0, "BOffsetX": 0.0, "BOffsetY": 0.0}]}')
    (tmp_path / "cells.json").write_text(cells)
    for k, calibration in enumerate([example, tmp_path / "cells.json"]):
        run("web", quilt_file, "--looking-glass", calibration, "-o", tmp_path / f"page{k}")
        run("interlace", quilt_file, "--looking-glass", calibration, "-q", "-o", tmp_path / f"native{k}.png")
        (shown,) = capture(tmp_path / f"page{k}", ["#show=looking-glass"], tmp_path / f"shots{k}")
        native = holoray.read_image(str(tmp_path / f"native{k}.png"))
        assert shown.shape[:2] == native.shape[:2] == (2048, 1536)
        assert psnr(shown, native) >= 40, calibration.name
    # Without a calibration the window shows the views (and says how to give one).
    run("web", quilt_file, "-o", tmp_path / "plain")
    (plain,) = capture(tmp_path / "plain", ["#show=looking-glass&u=3"], tmp_path / "plain_shots")
    quilt = holoray.read_image(str(quilt_file))[..., :3]
    assert psnr(plain, quilt[64:128, 3 * 48:4 * 48]) >= 45


def test_python_write_web_writes_the_page_the_cli_writes(tmp_path):
    scene = holoray.load_scene(PRIMITIVES)
    result = holoray.render(scene, holoray.LensArray(lenses=(24, 16), pixels_per_lens=6), threads=2)
    holoray.write_web(result, tmp_path / "from_python", name="primitives")
    # The CLI's page of the PNG `holoray render` writes of the same scene.
    run("render", PRIMITIVES, "--lenses", "24x16", "--pixels-per-lens", 6, "-q", "--threads", 2, "-o", tmp_path / "eia.png")
    run("web", tmp_path / "eia.png", "--pixels-per-lens", 6, "--name", "primitives", "-o", tmp_path / "from_cli")
    for f in ["index.html", "holoray_web.js", "light_field.json"]:
        assert (tmp_path / "from_python" / f).read_bytes() == (tmp_path / "from_cli" / f).read_bytes(), f
    for f in ["views.png", "eia.png"]:
        a = holoray.read_image(str(tmp_path / "from_python" / f))
        b = holoray.read_image(str(tmp_path / "from_cli" / f))
        assert np.array_equal(a, b), f
    with pytest.raises(ValueError, match="pixels_per_lens"):
        holoray.write_web(result.colour, tmp_path / "array")
    with pytest.raises(ValueError, match="not this camera's image"):
        holoray.write_web(holoray.render(scene, holoray.Pinhole((8, 8)), threads=2), tmp_path / "pinhole")


def test_the_page_names_what_it_shows_under_the_view(browser_ready, tmp_path):
    """Also the guide's picture: HOLORAY_WEB_SCREENSHOT=docs/images/web_page.png
    keeps the page's screenshot there (docs/guide/web.md)."""
    run("render", PRIMITIVES, "--lenses", "128x96", "--pixels-per-lens", 7, "-q", "--threads", 2, "-o", tmp_path / "eia.png")
    run("web", tmp_path / "eia.png", "--pixels-per-lens", 7, "--name", "primitives.nff", "-o", tmp_path / "page")
    shot = pathlib.Path(os.environ.get("HOLORAY_WEB_SCREENSHOT", tmp_path / "page.png")).resolve()
    (view,) = capture(tmp_path / "page", ["#u=1.5&v=3"], tmp_path / "shots", screenshot=shot)
    assert view.shape == (96, 128, 3)
    figures = (tmp_path / "shots" / "0.figures.txt").read_text().strip()
    assert figures == "primitives.nff: 128x96 lenses (square), 7 pixels per lens, 7x7 views", figures
    assert holoray.read_image(str(shot)).shape[:2] == (900, 1100)


def test_an_animations_frames_play_in_a_loop_and_each_can_be_held(browser_ready, tmp_path):
    shot = REPO / "examples" / "shots" / "swinging_box.toml"
    run("animate", shot, "-o", tmp_path / "frames", "--frames", "1:3", "-q", "--threads", 2)
    frames = sorted((tmp_path / "frames").glob("frame_*.png"))
    assert len(frames) == 3
    run("web", *frames, "--pixels-per-lens", 8, "--fps", 12, "-o", tmp_path / "page")
    manifest = (tmp_path / "page" / "light_field.json").read_text()
    assert '"fps": 12' in manifest and "views_0002.png" in manifest
    shown = capture(tmp_path / "page", [f"#frame={k}&u=2&v=5" for k in range(3)] + ["#frame=1&show=eia"], tmp_path / "shots")
    eias = [holoray.read_image(str(f))[..., :3] for f in frames]
    for k in range(3):
        assert psnr(shown[k], view_of(eias[k], 8, 2, 5)) >= 45, k
    assert psnr(shown[0], shown[2]) < 45  # the box moved
    assert psnr(shown[3], eias[1]) >= 45
    figures = (tmp_path / "shots" / "0.figures.txt").read_text().strip()
    assert figures.endswith("; 3 frames at 12 fps"), figures
    # Frames of another layout are refused, naming the frame.
    run("render", PRIMITIVES, "--lenses", "24x16", "--pixels-per-lens", 8, "-q", "-o", tmp_path / "other.png")
    done = subprocess.run([str(CLI), "web", str(frames[0]), str(tmp_path / "other.png"), "--pixels-per-lens", "8",
                           "-o", str(tmp_path / "bad")], capture_output=True, text=True)
    assert done.returncode == 1
    assert done.stderr.strip() == ("holoray: error: frame 1: eia of 8x8 views of 24x16 pixels, "
                                   "but frame 0 is eia of 8x8 views of 64x64"), done.stderr
