"""Four cameras on one scene: each render building the scene for itself
(holoray.render(scene, camera)) against one holoray.World built once and
rendered four times (holoray.render(world, camera)). The scene: a bumped
square of 707 x 707 quads (999,698 triangles) built from numpy, seen by
16x16-lens EIAs of 4, 6, 8 and 10 pixels a lens, so that the build is most
of each render. Both ways alternate 3 times; medians. The do-nothing
baseline: the mesh added to a Scene alone.
Usage, from the top of a checkout:
    PYTHONPATH=build/python /usr/bin/python3 bench/world_cameras.py [--device gpu]
"""
import statistics
import sys
import time

import numpy as np

import holoray

device = "gpu" if "--device" in sys.argv[1:] and sys.argv[-1] == "gpu" else "cpu"
n = 708
x, y = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
vertices = np.stack([x, y, 0.1 * np.sin(8 * x) * np.cos(8 * y)], axis=-1).reshape(-1, 3)
k = (np.arange(n - 1)[:, None] * n + np.arange(n - 1)[None, :]).ravel()
faces = np.concatenate([np.stack([k, k + 1, k + n + 1], 1), np.stack([k, k + n + 1, k + n], 1)])


def make_scene():
    scene = holoray.Scene()
    scene.add_mesh(vertices, faces)
    scene.add_light((0.0, -2.0, 3.0))
    scene.set_viewpoint((0.0, -2.0, 2.5), (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 40.0)
    return scene


t = time.perf_counter()
scene = make_scene()
baseline = time.perf_counter() - t
cameras = [holoray.LensArray(lenses=(16, 16), pixels_per_lens=p) for p in (4, 6, 8, 10)]


def each_its_own():
    for c in cameras:
        holoray.render(scene, c, device=device)


def one_world():
    world = holoray.World(scene)
    for c in cameras:
        holoray.render(world, c, device=device)


runs = {"each render builds the scene": [], "one World": []}
for _ in range(3):
    for name, way in (("each render builds the scene", each_its_own), ("one World", one_world)):
        t = time.perf_counter()
        way()
        runs[name].append(time.perf_counter() - t)
print(f"{len(faces)} triangles, {len(cameras)} cameras, device {device}")
for name, s in runs.items():
    print(f"{name}: median {statistics.median(s):.3f} s ({', '.join(f'{v:.3f}' for v in s)})")
first, second = (statistics.median(s) for s in runs.values())
print(f"one World is {first / second:.2f}x; the do-nothing baseline (the mesh added to a Scene): {baseline:.3f} s")
