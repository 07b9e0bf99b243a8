#!/usr/bin/env python3
"""Writes the example scenes examples/primitives.nff, examples/room.nff and
examples/swinging_box.gltf.

Primitives: the paper's test scene of every primitive kind (sphere, cone,
cylinder, polygons, smooth patches, a mirror and a glass object). Room: a
furnished room in the spirit of the paper's Room. Both are plain NFF
(shared/docs/nff-notes.md) and both straddle the lens array: the NFF `at`
point sits inside the scene, so orthoscopic EIAs show depth on both sides.
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def quad(out, a, b, c, d):
    out.append("p 4")
    for v in (a, b, c, d):
        out.append("%g %g %g" % v)


def box(out, lo, hi):
    """Six outward-wound faces of an axis-aligned box."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    quad(out, (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0))  # bottom (-z)
    quad(out, (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # top (+z)
    quad(out, (x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # front (-y)
    quad(out, (x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0))  # back (+y)
    quad(out, (x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # left (-x)
    quad(out, (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1))  # right (+x)


def patch_sphere(out, centre, r, n_lon=16, n_lat=10):
    """A low-polygon sphere of `pp` triangles with exact radial normals:
    smooth shading must make it look round."""
    cx, cy, cz = centre

    def vert(i, j):
        th = math.pi * j / n_lat
        ph = 2 * math.pi * i / n_lon
        n = (math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th))
        return (cx + r * n[0], cy + r * n[1], cz + r * n[2]), n

    for j in range(n_lat):
        for i in range(n_lon):
            a, b = vert(i, j), vert(i + 1, j)
            c, d = vert(i + 1, j + 1), vert(i, j + 1)
            # Counter-clockwise seen from outside.
            tris = []
            if j < n_lat - 1:  # the last band's d and c are both the south pole
                tris.append((a, d, c))
            if j > 0:  # the first band's a and b are both the north pole
                tris.append((a, c, b))
            for tri in tris:
                out.append("pp 3")
                for p, n in tri:
                    out.append("%.6g %.6g %.6g %.6g %.6g %.6g" % (p + n))


def primitives():
    o = ["# Primitives: every NFF primitive kind, a mirror and a glass object.",
         "# Written for holoray (examples/generate_examples.py).",
         "v", "from 0 -10 5.5", "at 0 0 1.2", "up 0 0 1", "angle 38", "hither 0.01", "resolution 512 512",
         "b 0.12 0.16 0.24",
         "l -6 -8 12", "l 9 -5 8 0.7 0.7 0.7"]
    # Floor: a checkerboard of polygons, two materials.
    light, dark = "f 0.85 0.82 0.75 0.9 0 1 0 1", "f 0.35 0.33 0.3 0.9 0 1 0 1"
    for parity, mat in ((0, light), (1, dark)):
        o.append(mat)
        for i in range(-5, 5):
            for j in range(-4, 6):
                if (i + j) % 2 == parity:
                    quad(o, (i, j, 0), (i + 1, j, 0), (i + 1, j + 1, 0), (i, j + 1, 0))
    o += ["# mirror wall at the back", "f 0.9 0.9 0.9 0.05 0.9 200 0 1"]
    quad(o, (-4.5, 5.5, 0), (4.5, 5.5, 0), (4.5, 5.5, 4.5), (-4.5, 5.5, 4.5))
    o += ["# red sphere with a highlight", "f 0.9 0.15 0.1 0.75 0.25 20 0 1", "s -2.4 0.8 1.2 1.2",
          "# glass sphere in front of the array", "f 0.95 0.97 1 0.05 0.1 200 0.85 1.5", "s 0.6 -2.6 1.0 1.0",
          "# green cone (apex radius 0: a true tip)", "f 0.2 0.75 0.3 0.8 0.1 10 0 1", "c 2.6 2.2 0 1.0 2.6 2.2 2.8 0",
          "# blue open cylinder", "f 0.2 0.35 0.9 0.7 0.3 30 0 1", "c -3.6 -1.8 0 0.55 -3.6 -1.8 2.4 0.55",
          "# yellow standing star: a concave polygon", "f 0.95 0.8 0.1 0.9 0 1 0 1"]
    star = []
    for k in range(10):
        a = math.pi / 2 + k * math.pi / 5
        r = 1.1 if k % 2 == 0 else 0.45
        star.append((3.3 + r * math.cos(a), -1.2, 1.3 + r * math.sin(a)))
    # Wind counter-clockwise as seen from the viewer (-y side).
    o.append("p %d" % len(star))
    o += ["%g %g %g" % v for v in reversed(star)]
    o += ["# smooth patches: a polygonal sphere shaded with vertex normals", "f 0.8 0.5 0.9 0.8 0.2 15 0 1"]
    patch_sphere(o, (0.2, 1.8, 1.0), 1.0)
    return o


def room():
    o = ["# Room: a furnished room in the spirit of the paper's Room scene.",
         "# Written for holoray (examples/generate_examples.py).",
         "v", "from 0.5 -7.5 2.6", "at 0 1.2 1.3", "up 0 0 1", "angle 55", "hither 0.01", "resolution 512 512",
         "b 0 0 0",
         "l -1.5 0.5 3.6", "l 2.5 -3 3.4 0.6 0.6 0.6"]
    W, D, H = 4.0, 4.5, 3.0  # half width, depth, height
    o.append("f 0.6 0.45 0.3 0.9 0.05 5 0 1")  # wooden floor
    quad(o, (-W, -D, 0), (W, -D, 0), (W, D, 0), (-W, D, 0))
    o.append("f 0.9 0.9 0.85 0.9 0 1 0 1")  # ceiling, faces down
    quad(o, (-W, -D, H), (-W, D, H), (W, D, H), (W, -D, H))
    o.append("f 0.75 0.8 0.9 0.9 0 1 0 1")  # back wall
    quad(o, (-W, D, 0), (W, D, 0), (W, D, H), (-W, D, H))
    o.append("f 0.9 0.7 0.6 0.9 0 1 0 1")  # left and right walls
    quad(o, (-W, -D, 0), (-W, D, 0), (-W, D, H), (-W, -D, H))
    quad(o, (W, -D, 0), (W, -D, H), (W, D, H), (W, D, 0))
    o.append("# a mirror on the back wall")
    o.append("f 0.9 0.9 0.9 0.05 0.85 200 0 1")
    quad(o, (0.8, D - 0.01, 0.8), (3.2, D - 0.01, 0.8), (3.2, D - 0.01, 2.4), (0.8, D - 0.01, 2.4))
    o += ["# table: a box top on four cylinder legs", "f 0.45 0.3 0.18 0.8 0.2 20 0 1"]
    box(o, (-1.6, 0.2, 0.9), (1.2, 2.0, 1.0))
    for x, y in ((-1.45, 0.35), (1.05, 0.35), (-1.45, 1.85), (1.05, 1.85)):
        o.append("c %g %g 0 0.07 %g %g 0.9 0.07" % (x, y, x, y))
    o += ["# things on the table", "f 0.85 0.15 0.15 0.7 0.3 30 0 1", "s -0.9 1.1 1.25 0.25",
          "f 0.95 0.97 1 0.05 0.1 200 0.85 1.5", "s 0.3 0.8 1.2 0.2",
          "f 0.95 0.85 0.2 0.8 0.2 40 0 1", "c 0.6 1.6 1.0 0.18 0.6 1.6 1.5 0.05"]
    o += ["# a cabinet on the left", "f 0.3 0.5 0.35 0.85 0.1 10 0 1"]
    box(o, (-3.9, 1.5, 0), (-2.9, 4.4, 1.8))
    o += ["# a ball on the floor, in front of the array", "f 0.2 0.4 0.9 0.6 0.4 40 0 1", "s 1.6 -2.2 0.45 0.45",
          "# a hanging lamp", "f 0.95 0.95 0.7 0.9 0.1 10 0 1", "c -0.2 1.1 3.0 0.02 -0.2 1.1 2.4 0.02",
          "c -0.2 1.1 2.4 0.05 -0.2 1.1 2.1 0.4"]
    return o


def swinging_box():
    """box_on_floor.obj as glTF 2.0 with node animation (docs/mesh-import.md,
    "Node animation"): the red box slides across the floor and turns half a
    turn about the vertical (y) in 2 s; a KHR_lights_punctual point light of
    100,000 cd (glTF lights are in candela: about unit radiance on the white
    floor 7 units away; at 1 cd, as first written, the scene rendered black).
    Played by examples/shots/swinging_box.toml."""
    buf = bytearray()
    views, accessors = [], []

    def accessor(fmt, values, typ, component, extra=None):
        data = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v)
                        for v in values)
        views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data)})
        buf.extend(data)
        a = {"bufferView": len(views) - 1, "componentType": component, "count": len(values), "type": typ}
        a.update(extra or {})
        accessors.append(a)
        return len(accessors) - 1

    def mesh(positions, indices, material):
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        pa = accessor("3f", positions, "VEC3", 5126, {"min": lo, "max": hi})
        ia = accessor("I", indices, "SCALAR", 5125)
        return {"primitives": [{"attributes": {"POSITION": pa}, "indices": ia, "material": material}]}

    cube = [(x, y, z) for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    cube_idx = [i for a, b, c, d in faces for i in (a, b, c, a, c, d)]
    floor = [(-4, -1.01, -4), (4, -1.01, -4), (4, -1.01, 4), (-4, -1.01, 4)]
    times = [0.0, 1.0, 2.0]
    t_in = accessor("f", times, "SCALAR", 5126, {"min": [0.0], "max": [2.0]})
    slide = accessor("3f", [(-2, -0.26, 0), (0, -0.26, 1), (2, -0.26, 0)], "VEC3", 5126)  # resting on the floor
    turn = accessor("4f", [(0, math.sin(a / 2), 0, math.cos(a / 2)) for a in (0, math.pi / 2, math.pi)], "VEC4", 5126)
    gltf = {
        "asset": {"version": "2.0", "generator": "examples/generate_examples.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 1, 1], "intensity": 100000}]}},
        "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"name": "floor", "mesh": 1}, {"name": "box", "mesh": 0, "scale": [0.75, 0.75, 0.75]},
                  {"name": "light", "translation": [3, 5, 4], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "meshes": [mesh(cube, cube_idx, 0), mesh(floor, [0, 2, 1, 0, 3, 2], 1)],
        "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.15, 0.1, 1], "metallicFactor": 0}},
                      {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.65, 1], "metallicFactor": 0}}],
        "animations": [{"name": "swing",
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}},
                                     {"sampler": 1, "target": {"node": 1, "path": "rotation"}}],
                        "samplers": [{"input": t_in, "output": slide}, {"input": t_in, "output": turn}]}],
        "buffers": [{"byteLength": len(buf),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
        "bufferViews": views, "accessors": accessors,
    }
    return json.dumps(gltf, indent=1)


for name, lines in (("primitives.nff", primitives()), ("room.nff", room())):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("\n".join(lines) + "\n")
with open(os.path.join(HERE, "swinging_box.gltf"), "w") as f:
    f.write(swinging_box() + "\n")
