#!/usr/bin/env python3
"""Wall time of holoray and tachyon-nox on the same Tachyon scenes, same
work: a pinhole view (the scene's own camera) at SIZE x SIZE, one sample per
pixel, every core, PNG written. Whole processes, runs alternated, median of
N; the do-nothing baseline is each program's start and exit (holoray
--help, tachyon-nox on an empty scene). Also holoray's EIA of the same size
(SIZE/8 lenses square x 8 px).
Usage: python3 bench/tachyon_speed.py HOLORAY SCENE.dat... [--runs N] [--size S]
Prints a markdown table."""
import os
import statistics
import subprocess
import sys
import tempfile
import time

args = sys.argv[1:]
runs = 5
if "--runs" in args:
    i = args.index("--runs")
    runs = int(args[i + 1])
    del args[i:i + 2]
size = 2048
if "--size" in args:
    i = args.index("--size")
    size = int(args[i + 1])
    del args[i:i + 2]
holoray, scenes = os.path.abspath(args[0]), args[1:]
out = tempfile.mkdtemp()


def wall(cmd, cwd):
    t = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t


with open(f"{out}/empty.dat", "w") as f:
    f.write("begin_scene resolution 1 1 end_scene\n")
start = {"tachyon": [], "holoray": []}
for _ in range(runs):
    start["tachyon"].append(wall(["tachyon-nox", "empty.dat", "-format", "PNG", "-o", f"{out}/n.png"], out))
    start["holoray"].append(wall([holoray, "--help"], out))
print(f"Do-nothing baselines (median of {runs}): tachyon-nox on an empty scene "
      f"{statistics.median(start['tachyon']):.3f} s, holoray --help {statistics.median(start['holoray']):.3f} s.")
print()
print(f"| scene ({size}x{size}) | tachyon-nox pinhole s | holoray pinhole s | holoray / tachyon | holoray EIA s |")
print("|---|---:|---:|---:|---:|")
for scene in scenes:
    cwd, name = os.path.dirname(os.path.abspath(scene)), os.path.basename(scene)
    cmds = {
        "tachyon": ["tachyon-nox", name, "-aasamples", "0", "-res", str(size), str(size), "-format", "PNG",
                    "-o", f"{out}/t.png"],
        "pinhole": [holoray, "render", name, "--camera", "pinhole", "--resolution", f"{size}x{size}", "-o",
                    f"{out}/h.png", "-q"],
        "eia": [holoray, "render", name, "--lenses", f"{size // 8}x{size // 8}", "-o", f"{out}/e.png", "-q"],
    }
    times = {k: [] for k in cmds}
    for _ in range(runs):
        for k, c in cmds.items():
            times[k].append(wall(c, cwd))
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"| {name} | {med['tachyon']:.3f} | {med['pinhole']:.3f} | {med['pinhole'] / med['tachyon']:.2f} | {med['eia']:.3f} |")
