#!/usr/bin/env python3
"""How well each schedule of the GPU path's rays would fill a subgroup's lanes.

Reads a ray log written by the GPU path (HOLORAY_GPU_RAY_LOG=FILE: each
traversal's pixel, kind, depth and BVH nodes visited, trace.comp's kRayLog)
and gives, for subgroups of LANES lanes, the lanes' use of the traversal's
node steps (nodes visited over the steps the subgroup takes times its lanes:
1 when no lane ever waits) under four schedules:

- today's kernel, lanes in step by their pixel's whole ray tree (a lower
  bound of its waste: each lane's traversals as if they ran back to back),
- today's kernel, each lane's k-th ray traversed in step with the others'
  k-th (its subgroups' lanes wait on the longest of each),
- with --ppl P, today's kernel with each band's pixels dealt in
  sub-aperture order (consecutive invocations taking the same pixel of
  consecutive lenses of P x P pixels), both ways above,
- a wavefront: a queue per ray kind and depth, each in pixel order, cut into
  subgroups of LANES rays,
- the wavefront with ray fetch (a lane takes the queue's next ray when its
  own is done, after Aila and Laine 2009): its ceiling, every lane busy.

Only the traversal's node steps are modelled: not shading, not the queues'
memory traffic, not a node's cost. See docs/design/gpu.md.

Usage: HOLORAY_GPU_RAY_LOG=/tmp/balls.raylog build/bench/holoray_gpu_frames \\
           SCENE --device gpu --lenses 60x34 --ppl 16 --frames 1 --warmup 0
       /usr/bin/python3 bench/ray_schedule_model.py /tmp/balls.raylog [--lanes 32]
"""
import argparse
import sys

import numpy as np


def read_log(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"HRRAYLG1" or len(data) < 32:
        sys.exit(f"ray_schedule_model.py: {path}: not a ray log (HOLORAY_GPU_RAY_LOG writes them)")
    wx, wy, width, height, kept, dropped = np.frombuffer(data, np.uint32, 6, 8)
    if dropped:
        sys.exit(f"ray_schedule_model.py: {path}: {dropped} of {kept + dropped} rays did not fit the log; log a smaller image")
    rec = np.frombuffer(data, np.uint32, 4 * int(kept), 32).reshape(-1, 4).astype(np.int64)
    return int(wx), int(wy), int(width), int(height), rec


def subgroup_steps(groups, nodes):
    """Steps x lanes' sum over groups: each group takes its longest member's nodes."""
    _, inverse = np.unique(groups, return_inverse=True)
    longest = np.zeros(inverse.max() + 1 if len(inverse) else 0, np.int64)
    np.maximum.at(longest, inverse, nodes)
    return longest


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("log")
    parser.add_argument("--lanes", type=int, default=32, help="a subgroup's lanes (NVIDIA 32, AMD 32 or 64, lavapipe 8)")
    parser.add_argument("--ppl", type=int, default=0, help="a square array's pixels per lens: model sub-aperture order too")
    args = parser.parse_args()
    lanes = args.lanes
    wx, wy, width, height, rec = read_log(args.log)
    i, j = rec[:, 0], rec[:, 1]
    frame, kind = rec[:, 2] >> 8, rec[:, 2] & 0xFF
    nodes = rec[:, 3] & 0xFFFF
    # Pixel order, each invocation's rays in the order it traced them (one
    # invocation's atomics keep its program order).
    order = np.lexsort((i, j, frame), axis=0)
    i, j, frame, kind, nodes = i[order], j[order], frame[order], kind[order], nodes[order]
    total = int(nodes.sum())
    if total == 0:
        sys.exit(f"ray_schedule_model.py: {args.log}: no node visited")
    # Today's kernel: an invocation per pixel, workgroups of wx x wy, a
    # subgroup LANES consecutive invocations of a workgroup.
    pixel = (frame * (height + wy) + j) * (width + wx) + i
    first = np.r_[True, pixel[1:] != pixel[:-1]]
    pixel_id = np.cumsum(first) - 1
    ray_k = np.arange(len(pixel)) - np.flatnonzero(first)[pixel_id]
    per_pixel = np.bincount(pixel_id, weights=nodes).astype(np.int64)
    def today(ii, jj):
        local = (ii % wx) + (jj % wy) * wx
        group = ((frame * ((height + wy - 1) // wy + 1) + jj // wy) * ((width + wx - 1) // wx + 1) + ii // wx) * 1024 + local // lanes
        whole = subgroup_steps(group[first], per_pixel).sum() * lanes
        return whole, subgroup_steps(group * 4096 + np.minimum(ray_k, 4095), nodes).sum() * lanes

    whole_tree, in_step = today(i, j)
    schedules = [("today's kernel: lanes in step by whole ray tree (its lower bound)", whole_tree),
                 ("today's kernel: each lane's k-th ray in step", in_step)]
    if args.ppl > 0:
        # gpu_renderer.cpp's bands, and in each the pixel x of n dealt to
        # invocation (x mod P) L + x div P (L: lenses across the band).
        p = args.ppl
        band_rows = max(8, (1 << 20) // max(1, width) // 8 * 8)
        def dealt(x, n):
            lenses = (n + p - 1) // p
            return (x % p) * lenses + x // p
        rows_in_band = np.minimum(band_rows, height - j // band_rows * band_rows)
        sub_i = dealt(i, width)
        sub_j = j // band_rows * band_rows + dealt(j % band_rows, rows_in_band)
        sub_whole, sub_step = today(sub_i, sub_j)
        schedules += [(f"sub-aperture order ({p} px a lens): lanes in step by whole ray tree", sub_whole),
                      (f"sub-aperture order ({p} px a lens): each lane's k-th ray in step", sub_step)]
    # The wavefront: a queue per kind and depth, in pixel order.
    queued = 0
    rows = []
    for k in np.unique(kind):
        q = nodes[kind == k]
        padded = np.zeros((len(q) + lanes - 1) // lanes * lanes, np.int64)
        padded[: len(q)] = q
        steps = padded.reshape(-1, lanes).max(axis=1).sum() * lanes
        queued += steps
        name = ("shadow" if k & 0x80 else "radiance") + f" depth {k & 0x7F}"
        rows.append((name, len(q), q.mean(), q.sum() / steps))
    print(f"Ray log: {args.log}: {width}x{height}, workgroups {wx}x{wy}, {len(nodes)} rays, "
          f"{total / len(nodes):.2f} nodes a ray; subgroups of {lanes} lanes")
    print()
    print("| schedule | lanes' use of node steps | today's steps (k-th ray in step) over these |")
    print("|---|---:|---:|")
    schedules += [("wavefront: a queue per kind and depth, pixel order", queued),
                  ("wavefront with ray fetch (ceiling)", total)]
    for name, steps in schedules:
        print(f"| {name} | {total / steps:.3f} | {in_step / steps:.2f}x |")
    print()
    print("| queue | rays | nodes a ray | lanes' use in the queue |")
    print("|---|---:|---:|---:|")
    for name, n, mean, use in rows:
        print(f"| {name} | {n} | {mean:.2f} | {use:.3f} |")


if __name__ == "__main__":
    main()
