#!/usr/bin/env python3
"""A light-field data set from one scene: N random placements of a lens array.

Each sample jitters the viewpoint that places the array (the eye moves in a
ball around the base eye, still looking at `at`) and draws the lens field of
view, renders the EIA with its depth AOV, and writes sample_NNNN.npz holding
  colour       (H, W, 3) float32, linear RGB: the EIA
  depth        (H, W) float32, the line parameter t of each pixel, NaN on background
  light_field  (P, P, Ny, Nx, 3) float32: light_field[v, u] is sub-aperture view (u, v)
  eye, at, up, fov_deg, lenses, pixels_per_lens, fov_lens: the camera.
The base viewpoint is the scene's NFF `v` block (or --eye/--at/--up/--fov).

Run from the top of a checkout, after scripts/setup.sh:
  PYTHONPATH=build/python /usr/bin/python3 examples/python/light_field_dataset.py -o dataset/
Guide: docs/guide/python.md.
"""
import argparse
from pathlib import Path

import numpy as np

import holoray

ROOT = Path(__file__).resolve().parents[2]


def nff_viewpoint(path):
    """from, at, up and angle of an NFF file's `v` block; None for other formats."""
    if path.suffix.lower() != ".nff":
        return None
    view = {}
    for line in path.read_text().splitlines():
        words = line.split()
        if words and words[0] in ("from", "at", "up", "angle") and words[0] not in view:
            view[words[0]] = [float(w) for w in words[1:]]
        if len(view) == 4:
            return view["from"], view["at"], view["up"], view["angle"][0]
    return None


def vector(text):
    return [float(x) for x in text.split(",")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", type=Path, default=ROOT / "examples" / "primitives.nff")
    parser.add_argument("--count", type=int, default=8, help="samples to render (8)")
    parser.add_argument("--lenses", type=int, default=32, help="lenses across and down (32)")
    parser.add_argument("--pixels-per-lens", type=int, default=8, help="P (8)")
    parser.add_argument("--fov-lens", type=float, nargs=2, default=(15.0, 30.0), metavar=("MIN", "MAX"),
                        help="range of the lens field of view, degrees (15 30)")
    parser.add_argument("--jitter", type=float, default=0.15,
                        help="radius of the eye's ball, as a share of |eye - at| (0.15)")
    parser.add_argument("--eye", type=vector, help="X,Y,Z (default: the NFF's from)")
    parser.add_argument("--at", type=vector, help="X,Y,Z (default: the NFF's at)")
    parser.add_argument("--up", type=vector, help="X,Y,Z (default: the NFF's up)")
    parser.add_argument("--fov", type=float, help="vertical field of view, degrees (default: the NFF's angle)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (0)")
    parser.add_argument("-o", "--output", type=Path, required=True, help="folder for sample_NNNN.npz")
    args = parser.parse_args()

    base = nff_viewpoint(args.scene) or (None, None, None, None)
    eye0, at, up, fov = (given if given is not None else default
                         for given, default in zip((args.eye, args.at, args.up, args.fov), base))
    if None in (eye0, at, up, fov):
        parser.error(f"{args.scene} has no NFF viewpoint: give --eye, --at, --up and --fov")
    eye0, at, up = (np.array(v, dtype=float) for v in (eye0, at, up))
    radius = args.jitter * np.linalg.norm(eye0 - at)
    P, n = args.pixels_per_lens, args.lenses
    rng = np.random.default_rng(args.seed)
    args.output.mkdir(parents=True, exist_ok=True)

    for k in range(args.count):
        # A uniform point in the ball of the given radius around the base eye.
        offset = rng.normal(size=3)
        offset *= radius * rng.uniform() ** (1 / 3) / np.linalg.norm(offset)
        eye = eye0 + offset
        fov_lens = rng.uniform(*args.fov_lens)
        # A fresh scene per sample: set_viewpoint then places everything the
        # viewpoint places (the array, and a headlight in a scene without lights).
        scene = holoray.load_scene(args.scene)
        scene.set_viewpoint(eye, at, up, float(fov))
        camera = holoray.LensArray(lenses=(n, n), pixels_per_lens=P, fov_lens=fov_lens)
        result = holoray.render(scene, camera, aovs=("depth",))
        depth = result.aovs["depth"]
        name = args.output / f"sample_{k:04d}.npz"
        np.savez(name, colour=result.colour, depth=depth,
                 light_field=holoray.light_field(result.colour, P),
                 eye=eye, at=at, up=up, fov_deg=fov, lenses=np.array((n, n)),
                 pixels_per_lens=P, fov_lens=fov_lens)
        t = depth[np.isfinite(depth)]
        span = f"t {t.min():.3f} to {t.max():.3f} on {t.size / depth.size:.0%} of pixels" if t.size else "background only"
        print(f"{name}: eye ({eye[0]:.3f}, {eye[1]:.3f}, {eye[2]:.3f}), fov_lens {fov_lens:.1f} deg, {span}, "
              f"trace {result.stats['seconds']['trace']:.3f} s")


if __name__ == "__main__":
    main()
