"""The screenshots' scene: the tests' textured cube on a plane, a 96x64-lens
EIA of 8 px per lens with the depth pass, saved where the first argument
after `--` says."""
import os
import sys

import bpy

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests", "blender"))
import scene  # noqa: E402

sc = scene.build()
h = sc.holoray
h.lenses_x, h.lenses_y, h.pixels_per_lens = 96, 64, 8
h.aov_depth = True
bpy.ops.wm.save_as_mainfile(filepath=sys.argv[sys.argv.index("--") + 1])
