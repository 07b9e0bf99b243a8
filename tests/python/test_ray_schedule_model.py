"""bench/ray_schedule_model.py on ray logs whose lanes' use is known by hand:
the subgroups it forms, its two bounds of today's kernel, the wavefront's
queues and its refusals. (The GPU path's own logs are held to the frame's
counts by tests/test_gpu_path.cpp, TheRayLogHoldsEveryTraversal...)"""
from __future__ import annotations

import re
import subprocess
import sys

import numpy as np

from conftest import REPO

MODEL = REPO / "bench" / "ray_schedule_model.py"


def write_log(path, width, height, records, workgroup=(32, 2), dropped=0):
    """A log as the GPU path writes it: records of (i, j, kind, nodes)."""
    rec = np.array([(i, j, kind, nodes) for i, j, kind, nodes in records], np.uint32).reshape(-1, 4)
    head = np.array([*workgroup, width, height, len(rec), dropped], np.uint32)
    path.write_bytes(b"HRRAYLG1" + head.tobytes() + rec.tobytes())
    return path


def lanes_use(path, *args):
    out = subprocess.run([sys.executable, str(MODEL), str(path), *args], check=True, capture_output=True, text=True).stdout
    return {m.group(1): float(m.group(2)) for m in re.finditer(r"^\| ([^|]+?) \| ([0-9.]+) \| [0-9.]+x \|$", out, re.M)}


def row(use, start):
    (value,) = [v for k, v in use.items() if k.startswith(start)]
    return value


def test_one_long_ray_keeps_its_subgroup_waiting(tmp_path):
    # A 64x2 image in 32x2 workgroups: subgroups of 32 are the rows' halves.
    # Every pixel one eye ray of 1 node, but pixel (0, 0): 33 nodes.
    recs = [(i, j, 1, 33 if (i, j) == (0, 0) else 1) for j in range(2) for i in range(64)]
    use = lanes_use(write_log(tmp_path / "a.raylog", 64, 2, recs))
    total, steps = 127 + 33, 33 * 32 + 3 * 32
    assert abs(row(use, "today's kernel: lanes in step by whole") - total / steps) < 5e-4
    assert abs(row(use, "today's kernel: each lane's k-th") - total / steps) < 5e-4
    assert abs(row(use, "wavefront: a queue") - total / steps) < 5e-4
    assert row(use, "wavefront with ray fetch") == 1.0


def test_rays_in_step_wait_on_each_others_longest_while_whole_trees_do_not(tmp_path):
    # Two lanes of one subgroup: pixel 0 traces rays of 10 then 1 nodes,
    # pixel 1 of 1 then 12. Whole trees in step: 13 steps; ray by ray: 10 + 12.
    recs = [(0, 0, 1, 10), (0, 0, 2, 1), (1, 0, 1, 1), (1, 0, 2, 12)]
    use = lanes_use(write_log(tmp_path / "b.raylog", 32, 1, recs))
    assert abs(row(use, "today's kernel: lanes in step by whole") - 24 / (13 * 32)) < 5e-4
    assert abs(row(use, "today's kernel: each lane's k-th") - 24 / (22 * 32)) < 5e-4
    # The wavefront: depth 1 (10, 1) and depth 2 (1, 12), each its own subgroup.
    assert abs(row(use, "wavefront: a queue") - 24 / (22 * 32)) < 5e-4


def test_sub_aperture_order_deals_the_same_pixel_of_neighbouring_lenses_together(tmp_path):
    # 32 lenses of 2 px across one row: the long rays sit at pixel 0 of every
    # lens. The image's order puts a long and a short ray in every pair of
    # lanes; sub-aperture order puts all 32 long ones in one subgroup.
    recs = [(i, 0, 1, 9 if i % 2 == 0 else 1) for i in range(64)]
    use = lanes_use(write_log(tmp_path / "c.raylog", 64, 1, recs, workgroup=(32, 1)), "--ppl", "2")
    total = 32 * 9 + 32
    assert abs(row(use, "today's kernel: each lane's k-th") - total / (2 * 9 * 32)) < 5e-4
    assert abs(row(use, "sub-aperture order (2 px a lens): each lane's k-th") - total / (9 * 32 + 32)) < 5e-4


def test_refuses_a_log_that_lost_rays_and_a_file_that_is_no_log(tmp_path):
    lost = write_log(tmp_path / "d.raylog", 32, 1, [(0, 0, 1, 3)], dropped=5)
    r = subprocess.run([sys.executable, str(MODEL), str(lost)], capture_output=True, text=True)
    assert r.returncode == 1
    assert r.stderr.strip() == f"ray_schedule_model.py: {lost}: 5 of 6 rays did not fit the log; log a smaller image"
    other = tmp_path / "e.raylog"
    other.write_bytes(b"P6\n1 1\n255\n\0\0\0" + bytes(32))
    r = subprocess.run([sys.executable, str(MODEL), str(other)], capture_output=True, text=True)
    assert r.returncode == 1
    assert r.stderr.strip() == f"ray_schedule_model.py: {other}: not a ray log (HOLORAY_GPU_RAY_LOG writes them)"
