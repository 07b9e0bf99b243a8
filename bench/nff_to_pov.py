#!/usr/bin/env python3
"""NFF (Eric Haines' SPD) to POV-Ray 3.7 scene, for the benchmark's POV-Ray
yardstick (issue 4): the same geometry, lights and Whitted materials
(Kd, Ks as mirror and highlight, transmittance with its index), ray depth 5,
no anti-aliasing. Polygons become triangle fans in one mesh (pp: smooth
triangles). It converts for timing, not for a pixel-exact match.

Usage: python3 bench/nff_to_pov.py scene.nff > scene.pov
"""
import math
import sys


def tokens(text):
    for line in text.splitlines():
        line = line.split("#", 1)[0]
        yield from line.split()


def convert(text):
    tok = tokens(text)
    nxt = lambda: next(tok)
    num = lambda: float(nxt())
    vec = lambda: (num(), num(), num())
    out, lights, tris = [], [], []
    material = "texture { pigment { rgb 0.8 } finish { diffuse 1 } }"
    view = None
    background = (0, 0, 0)
    objects = 0
    for kw in tok:
        if kw == "v":
            v = {}
            for key in ("from", "at", "up", "angle", "hither", "resolution"):
                if nxt() != key:
                    raise SystemExit(f"expected '{key}' in the view")
                v[key] = (num(), num()) if key == "resolution" else num() if key in ("angle", "hither") else vec()
            view = v
        elif kw == "b":
            background = vec()
        elif kw == "l":
            pos = vec()
            lights.append(pos)
        elif kw == "f":
            c, kd, ks, shine, t, ior = vec(), num(), num(), num(), num(), num()
            interior = f" interior {{ ior {ior:g} }}" if t > 0 else ""
            material = (f"texture {{ pigment {{ rgb <{c[0]:g},{c[1]:g},{c[2]:g}> transmit {t:g} }} "
                        f"finish {{ ambient {kd:g} diffuse {kd:g} phong {ks:g} phong_size {max(shine, 1):g} "
                        f"reflection {ks:g} }} }}{interior}")
        elif kw == "s":
            c, r = vec(), num()
            out.append(f"sphere {{ <{c[0]:g},{c[1]:g},{c[2]:g}>, {abs(r):g} {material} }}")
            objects += 1
        elif kw == "c":
            b, rb, a, ra = vec(), num(), vec(), num()
            out.append(f"cone {{ <{b[0]:g},{b[1]:g},{b[2]:g}>, {abs(rb):g}, <{a[0]:g},{a[1]:g},{a[2]:g}>, {abs(ra):g} open {material} }}")
            objects += 1
        elif kw in ("p", "pp"):
            n = int(nxt())
            verts, norms = [], []
            for _ in range(n):
                verts.append(vec())
                if kw == "pp":
                    norms.append(vec())
            body = []
            for k in range(1, n - 1):
                i = (0, k, k + 1)
                if kw == "pp":
                    body.append("smooth_triangle { " + ", ".join(
                        f"<{verts[j][0]:g},{verts[j][1]:g},{verts[j][2]:g}>, <{norms[j][0]:g},{norms[j][1]:g},{norms[j][2]:g}>" for j in i) + " }")
                else:
                    body.append("triangle { " + ", ".join(f"<{verts[j][0]:g},{verts[j][1]:g},{verts[j][2]:g}>" for j in i) + " }")
            out.append("mesh { " + " ".join(body) + f" {material} }}")
            objects += 1
        else:
            raise SystemExit(f"unknown NFF keyword '{kw}'")
    if view is None:
        raise SystemExit("no viewpoint")
    n = max(1, len(lights))
    intensity = 1 / (2 * math.sqrt(n))  # the SPD's light and ambient intensity (nff-notes §4)
    f, a, u = view["from"], view["at"], view["up"]
    head = [
        "#version 3.7;",
        f"global_settings {{ assumed_gamma 1 max_trace_level 5 ambient_light rgb {intensity:g} }}",
        f"background {{ rgb <{background[0]:g},{background[1]:g},{background[2]:g}> }}",
        f"camera {{ perspective location <{f[0]:g},{f[1]:g},{f[2]:g}> sky <{u[0]:g},{u[1]:g},{u[2]:g}> "
        f"up y right -x look_at <{a[0]:g},{a[1]:g},{a[2]:g}> angle {view['angle']:g} }}",
    ]
    head += [f"light_source {{ <{p[0]:g},{p[1]:g},{p[2]:g}> rgb {intensity:g} }}" for p in lights]
    return "\n".join(head + out) + "\n", objects


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    text, count = convert(open(sys.argv[1]).read())
    sys.stdout.write(text)
    print(f"// {count} objects", file=sys.stderr)
