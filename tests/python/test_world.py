"""holoray.World: a scene built once, rendered through many cameras.

render(world, camera) must give what render(scene, camera) gives, bit for
bit, for every camera; a world's light options are fixed when it is built,
and a render's, left at their defaults, take them.
"""
from __future__ import annotations

import numpy as np
import pytest

import holoray
from conftest import REPO, THREADS

PRIMITIVES = str(REPO / "examples" / "primitives.nff")


def test_each_camera_on_a_world_renders_what_its_own_build_renders():
    scene = holoray.load_scene(PRIMITIVES)
    world = holoray.World(scene)
    assert world.build_seconds >= 0 and world.skipped_polygons == 0
    for camera in (holoray.LensArray(lenses=(16, 12), pixels_per_lens=4), holoray.Pinhole((64, 48))):
        shared = holoray.render(world, camera, threads=THREADS, aovs=["depth"])
        own = holoray.render(scene, camera, threads=THREADS, aovs=["depth"])
        np.testing.assert_array_equal(shared.colour, own.colour)
        np.testing.assert_array_equal(shared.aovs["depth"], own.aovs["depth"])
        assert shared.description == own.description


def test_a_render_takes_the_worlds_light_and_refuses_other():
    scene = holoray.load_scene(PRIMITIVES)
    world = holoray.World(scene, integrator="path", environment=(0.2, 0.3, 0.4), max_depth=3)
    camera = holoray.LensArray(lenses=16, pixels_per_lens=4)
    on_world = holoray.render(world, camera, threads=THREADS, spp=4)
    own = holoray.render(scene, camera, threads=THREADS, spp=4, integrator="path", environment=(0.2, 0.3, 0.4), max_depth=3)
    np.testing.assert_array_equal(on_world.colour, own.colour)
    with pytest.raises(ValueError, match="^max_depth: the world was built with other light options"):
        holoray.render(world, camera, max_depth=5)
    with pytest.raises(TypeError, match="expected a holoray.Scene or a holoray.World"):
        holoray.render("not a scene", camera)
