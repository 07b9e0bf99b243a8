"""Ten GPU renders of one 32x32-lens EIA (8 px a lens) of
examples/primitives.nff in one Python process: seconds per holoray.render
call, the first and the median of ten. Run it as is (the device and its
kernels kept between renders), then with HOLORAY_GPU_WORKGROUP=32x2 (the
default workgroup, but a measuring variable: every render makes its own
device), and with --cpu for the CPU's time on the same EIA.
Usage, from the top of a checkout:
    PYTHONPATH=build/python /usr/bin/python3 bench/gpu_renders_in_one_process.py [--cpu]
"""
import os
import statistics
import sys
import time

import holoray

device = "cpu" if "--cpu" in sys.argv[1:] else "gpu"
scene = holoray.load_scene("examples/primitives.nff")
camera = holoray.LensArray(lenses=(32, 32), pixels_per_lens=8)
seconds = []
for _ in range(10):
    start = time.perf_counter()
    holoray.render(scene, camera, device=device)
    seconds.append(time.perf_counter() - start)
how = "cpu" if device == "cpu" else ("a device each render" if "HOLORAY_GPU_WORKGROUP" in os.environ else "device kept")
print(f"{how}: first {seconds[0]:.3f} s, median of 10 {statistics.median(seconds):.3f} s")
