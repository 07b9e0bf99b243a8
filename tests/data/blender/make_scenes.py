#!/usr/bin/env python3
"""Writes the small glTF scenes that Blender renders as holoray's oracle
(render_oracle.py) and that tests/test_textures.cpp renders with holoray.

Standard library only. Each scene carries its own camera (square image, so
that Blender's sensor fit cannot differ from the file's yfov).

    python3 tests/data/blender/make_scenes.py   # rewrites the .gltf/.png here
"""
import base64
import functools
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def flat(rows):
    return [c for r in rows for c in r]


def add_accessor(blob, views, accessors, data, fmt, count, kind, target, minmax=None):
    """Appends `data` to the buffer `blob` (4-byte aligned) with a view and an
    accessor of it; returns the accessor's index."""
    while len(blob) % 4:
        blob.append(0)
    off = len(blob)
    blob.extend(data)
    views.append({"buffer": 0, "byteOffset": off, "byteLength": len(data), "target": target})
    acc = {"bufferView": len(views) - 1, "componentType": fmt, "count": count, "type": kind}
    if minmax:
        acc["min"], acc["max"] = minmax
    accessors.append(acc)
    return len(accessors) - 1


def vec3_accessor(add, rows, minmax=False):
    """A VEC3 float accessor of `rows` (with their bounds when `minmax`: positions)."""
    mm = ([min(p[i] for p in rows) for i in range(3)], [max(p[i] for p in rows) for i in range(3)]) if minmax else None
    return add(struct.pack("<%df" % (3 * len(rows)), *flat(rows)), 5126, len(rows), "VEC3", 34962, mm)


def floor_primitive(add, material):
    """A 6 x 6 square floor at y = 0 facing +y."""
    a_idx = add(struct.pack("<6H", 0, 2, 1, 0, 3, 2), 5123, 6, "SCALAR", 34963)
    pos = [[-3, 0, -3], [3, 0, -3], [3, 0, 3], [-3, 0, 3]]
    return {"attributes": {"POSITION": vec3_accessor(add, pos, True), "NORMAL": vec3_accessor(add, [[0, 1, 0]] * 4)},
            "indices": a_idx, "material": material}


def material(name, colour, metallic, roughness):
    """A glTF metallic-roughness material of constant factors."""
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour + [1], "metallicFactor": metallic,
                                                   "roughnessFactor": roughness}}


def write_gltf(name, gltf, blob, views, accessors):
    """Adds the one embedded buffer, its views and accessors to `gltf`, last,
    and writes NAME.gltf here."""
    gltf["buffers"] = [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]
    gltf["bufferViews"] = views
    gltf["accessors"] = accessors
    with open(os.path.join(HERE, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)


def write_png(path, width, height, rgb):
    """8-bit RGB (or RGBA, with 4-tuples) PNG, rows from the top; rgb is a
    list of (r, g, b[, a]) codes."""
    channels = len(rgb[0])
    raw = bytearray()
    for y in range(height):
        raw.append(0)
        for x in range(width):
            raw.extend(rgb[y * width + x])

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6 if channels == 4 else 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(bytes(raw), 9)))
        f.write(chunk(b"IEND", b""))


def orientation_texture(size=32):
    """Red grows with u (left to right), green with v (bottom to top of the
    image as glTF's v runs top to bottom: green grows downward in the file),
    and a blue square in the image's top-left corner (u, v near 0): a flip or
    a transposition of either axis changes the picture."""
    rgb = []
    for y in range(size):
        for x in range(size):
            r = int(255 * (x + 0.5) / size)
            g = int(255 * (y + 0.5) / size)
            b = 255 if (x < size // 4 and y < size // 4) else 40
            rgb.append((r, g, b))
    return rgb


def cube(half):
    """24 vertices (4 per face) with outward normals and each face's UVs
    covering the whole image, 36 indices counter-clockwise from outside."""
    faces = [  # normal, u axis, v axis (v axis points down the image: glTF)
        ((1, 0, 0), (0, 0, -1), (0, -1, 0)),
        ((-1, 0, 0), (0, 0, 1), (0, -1, 0)),
        ((0, 1, 0), (1, 0, 0), (0, 0, 1)),
        ((0, -1, 0), (1, 0, 0), (0, 0, -1)),
        ((0, 0, 1), (1, 0, 0), (0, -1, 0)),
        ((0, 0, -1), (-1, 0, 0), (0, -1, 0)),
    ]
    pos, nrm, uv, idx = [], [], [], []
    for n, a, b in faces:
        base = len(pos)
        for (su, sv) in ((0, 0), (1, 0), (1, 1), (0, 1)):
            p = [half * (n[i] + (2 * su - 1) * a[i] + (2 * sv - 1) * b[i]) for i in range(3)]
            pos.append(p)
            nrm.append(list(n))
            uv.append([su, sv])
        # (u, v) = (0,0),(1,0),(1,1): counter-clockwise seen from outside when a x b = -n.
        cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        if sum(cross[i] * n[i] for i in range(3)) < 0:
            idx += [base, base + 1, base + 2, base, base + 2, base + 3]
        else:
            idx += [base, base + 2, base + 1, base, base + 3, base + 2]
    return pos, nrm, uv, idx


def look_at_quaternion(eye, target):
    """Rotation (x, y, z, w) turning glTF's camera (looking down -z, up +y)
    toward target, with world +y as up."""
    f = [target[i] - eye[i] for i in range(3)]
    fl = math.sqrt(sum(c * c for c in f))
    f = [c / fl for c in f]
    z = [-c for c in f]
    up = [0, 1, 0]
    x = [up[1] * z[2] - up[2] * z[1], up[2] * z[0] - up[0] * z[2], up[0] * z[1] - up[1] * z[0]]
    xl = math.sqrt(sum(c * c for c in x))
    x = [c / xl for c in x]
    y = [z[1] * x[2] - z[2] * x[1], z[2] * x[0] - z[0] * x[2], z[0] * x[1] - z[1] * x[0]]
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1) * 2
        return [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = math.sqrt(1 + m[i][i] - m[j][j] - m[k][k]) * 2
    q = [0, 0, 0, 0]
    q[i] = s / 4
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    q[3] = (m[k][j] - m[j][k]) / s
    return q


def textured_box(name, wrap_s=10497, wrap_t=10497, uv_scale=1.0, transform=None):
    pos, nrm, uv, idx = cube(1.0)
    uv = [[u * uv_scale, v * uv_scale] for u, v in uv]
    blob = bytearray()
    views, accessors = [], []

    add = functools.partial(add_accessor, blob, views, accessors)
    a_pos = add(struct.pack("<%df" % (3 * len(pos)), *flat(pos)), 5126, len(pos), "VEC3", 34962,
                ([min(p[i] for p in pos) for i in range(3)], [max(p[i] for p in pos) for i in range(3)]))
    a_nrm = add(struct.pack("<%df" % (3 * len(nrm)), *flat(nrm)), 5126, len(nrm), "VEC3", 34962)
    a_uv = add(struct.pack("<%df" % (2 * len(uv)), *flat(uv)), 5126, len(uv), "VEC2", 34962)
    a_idx = add(struct.pack("<%dH" % len(idx), *idx), 5123, len(idx), "SCALAR", 34963)
    write_png(os.path.join(HERE, name + ".png"), 32, 32, orientation_texture(32))
    eye = [2.6, 2.1, 3.4]
    gltf = {
        "asset": {"version": "2.0", "generator": "holoray tests/data/blender/make_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [
            {"mesh": 0, "rotation": [0.0, 0.2588190451, 0.0, 0.9659258263]},
            {"camera": 0, "translation": eye, "rotation": look_at_quaternion(eye, [0, 0, 0])},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "TEXCOORD_0": a_uv},
                                    "indices": a_idx, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [1, 1, 1, 1],
                                                "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": wrap_s, "wrapT": wrap_t}],
        "images": [{"uri": name + ".png"}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
        "bufferViews": views,
        "accessors": accessors,
    }
    if transform:
        gltf["extensionsUsed"] = ["KHR_texture_transform"]
        gltf["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
            "KHR_texture_transform": transform}
    with open(os.path.join(HERE, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    return gltf, bytes(blob)


def embedded_copies(name, gltf, blob):
    """The same scene with its image inside: a data URI (NAME_datauri.gltf)
    and a GLB whose binary chunk holds the geometry and the image
    (NAME.glb). holoray must render all three alike."""
    with open(os.path.join(HERE, name + ".png"), "rb") as f:
        png = f.read()
    inline = json.loads(json.dumps(gltf))
    inline["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png).decode()}]
    with open(os.path.join(HERE, name + "_datauri.gltf"), "w") as f:
        json.dump(inline, f, indent=1)
    glb = json.loads(json.dumps(gltf))
    data = bytearray(blob)
    while len(data) % 4:
        data.append(0)
    glb["bufferViews"].append({"buffer": 0, "byteOffset": len(data), "byteLength": len(png)})
    data.extend(png)
    while len(data) % 4:
        data.append(0)
    glb["images"] = [{"bufferView": len(glb["bufferViews"]) - 1, "mimeType": "image/png"}]
    glb["buffers"] = [{"byteLength": len(data)}]
    text = json.dumps(glb).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(data), b"BIN\0") + bytes(data)
    with open(os.path.join(HERE, name + ".glb"), "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)


def masked_leaf(name):
    """The textured box behind a quad whose RGBA image is a green disc
    (alpha 255) on transparent ground (alpha 0), alphaMode MASK: the box is
    seen around the disc, and the disc casts a round shadow."""
    gltf, blob = textured_box(name)
    size = 32
    leaf = []
    for y in range(size):
        for x in range(size):
            inside = (x + 0.5 - size / 2) ** 2 + (y + 0.5 - size / 2) ** 2 < (size * 0.4) ** 2
            leaf.append((60, 160, 40, 255 if inside else 0))
    write_png(os.path.join(HERE, name + "_leaf.png"), size, size, leaf)
    blob = bytearray(blob)
    while len(blob) % 4:
        blob.append(0)
    quad = [(-0.45, -0.45, 0), (0.45, -0.45, 0), (0.45, 0.45, 0), (-0.45, 0.45, 0)]
    uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    nrm = [(0, 0, 1)] * 4
    idx = [0, 1, 2, 0, 2, 3]

    add = functools.partial(add_accessor, blob, gltf["bufferViews"], gltf["accessors"])
    a_pos = add(struct.pack("<12f", *flat(quad)), 5126, 4, "VEC3", 34962, ([-0.45, -0.45, 0], [0.45, 0.45, 0]))
    a_nrm = add(struct.pack("<12f", *flat(nrm)), 5126, 4, "VEC3", 34962)
    a_uv = add(struct.pack("<8f", *flat(uv)), 5126, 4, "VEC2", 34962)
    a_idx = add(struct.pack("<6H", *idx), 5123, 6, "SCALAR", 34963)
    gltf["meshes"].append({"primitives": [{"attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "TEXCOORD_0": a_uv},
                                           "indices": a_idx, "material": 1}]})
    gltf["materials"].append({"alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
                              "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}, "metallicFactor": 0.0,
                                                       "roughnessFactor": 1.0}})
    gltf["textures"].append({"sampler": 0, "source": 1})
    gltf["images"].append({"uri": name + "_leaf.png"})
    # The leaf between the camera and the box.
    gltf["nodes"].append({"mesh": 1, "translation": [1.3, 1.05, 1.7], "rotation": look_at_quaternion([0, 0, 0], [-2.6, -2.1, -3.4])})
    gltf["scenes"][0]["nodes"].append(2)
    gltf["buffers"][0] = {"byteLength": len(blob),
                          "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}
    with open(os.path.join(HERE, name + ".gltf"), "w") as f:
        json.dump(gltf, f, indent=1)


def uv_sphere(radius, centre, rings=24, segments=48):
    """A UV sphere with smooth (outward) normals, counter-clockwise from outside."""
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        theta = math.pi * i / rings
        for j in range(segments + 1):
            phi = 2 * math.pi * j / segments
            n = [math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)]
            nrm.append(n)
            pos.append([centre[k] + radius * n[k] for k in range(3)])
    row = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b = i * row + j, i * row + j + 1
            c, d = a + row, b + row
            if i > 0:
                idx += [a, c, b]
            if i < rings - 1:
                idx += [b, c, d]
    return pos, nrm, idx


def lit_spheres(name):
    """A metal (gold) and a dielectric (blue, glossy) sphere on a rough grey
    floor, under a sun and a warm spot (KHR_lights_punctual, photometric
    units): the oracle for glTF's metallic-roughness BRDF and its lights.
    The spheres stand inside the spot's inner cone, a narrow one: Blender's
    importer turns the cone into a blend that is not glTF's falloff, and
    Cycles dims a spot by the cosine of the angle off its axis."""
    blob = bytearray()
    views, accessors, meshes = [], [], []

    add = functools.partial(add_accessor, blob, views, accessors)

    def mesh(pos, nrm, idx, material):
        a_pos, a_nrm = vec3_accessor(add, pos, True), vec3_accessor(add, nrm)
        a_idx = add(struct.pack("<%dH" % len(idx), *idx), 5123, len(idx), "SCALAR", 34963)
        meshes.append({"primitives": [{"attributes": {"POSITION": a_pos, "NORMAL": a_nrm}, "indices": a_idx,
                                       "material": material}]})
        return len(meshes) - 1

    floor = mesh([[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]], [[0, 1, 0]] * 4, [0, 2, 1, 0, 3, 2], 0)
    gold = mesh(*uv_sphere(0.6, [-0.75, 0.6, 0]), 1)
    blue = mesh(*uv_sphere(0.6, [0.75, 0.6, 0.2]), 2)
    eye = [0.0, 2.2, 4.5]
    sun_dir = [-0.4, -1.0, -0.5]
    spot_at, spot_pos = [0.0, 0.3, 0.0], [4.0, 6.0, 4.0]
    gltf = {
        "asset": {"version": "2.0", "generator": "holoray tests/data/blender/make_scenes.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "color": [0.9, 0.95, 1.0], "intensity": 860.0},
            {"name": "spot", "type": "spot", "color": [1.0, 0.85, 0.7], "intensity": 70000.0,
             "spot": {"innerConeAngle": 0.22, "outerConeAngle": 0.3}},
        ]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3, 4, 5]}],
        "nodes": [
            {"mesh": floor},
            {"mesh": gold},
            {"mesh": blue},
            {"camera": 0, "translation": eye, "rotation": look_at_quaternion(eye, [0, 0.5, 0])},
            {"name": "sun", "rotation": look_at_quaternion([0, 0, 0], sun_dir),
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"name": "spot", "translation": spot_pos, "rotation": look_at_quaternion(spot_pos, spot_at),
             "extensions": {"KHR_lights_punctual": {"light": 1}}},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": meshes,
        "materials": [
            material("floor", [0.6, 0.6, 0.6], 0.0, 0.9),
            material("gold", [1.0, 0.71, 0.29], 1.0, 0.35),
            material("blue", [0.1, 0.3, 0.8], 0.0, 0.3),
        ],
    }
    write_gltf(name, gltf, blob, views, accessors)


def quat_axis(axis, angle):
    """Unit quaternion (x, y, z, w) of a rotation by `angle` radians about a unit axis."""
    s = math.sin(angle / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]


SKIN_FRAMES = 10
SKIN_FPS = 24


def tube(x0, x1, rings, segments, radius, y):
    """A tube of `radius` along x from x0 to x1 at height y, open ends,
    outward normals, counter-clockwise from outside."""
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        x = x0 + (x1 - x0) * i / rings
        for j in range(segments):
            a = 2 * math.pi * j / segments
            n = [0.0, math.cos(a), math.sin(a)]
            pos.append([x, y + radius * n[1], radius * n[2]])
            nrm.append(n)
    for i in range(rings):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            idx += [a, b, d, a, d, c]
    return pos, nrm, idx


def skinned_arm(name):
    """An arm of two skinned primitives (orange upper arm, blue forearm)
    over a grey floor, bent by two joints over SKIN_FRAMES frames at
    SKIN_FPS: the shoulder turns 25 degrees about y, the elbow 100 degrees
    about z, one key per frame. Vertices within 0.3 of the elbow blend both
    joints linearly (weights summing to 1). The oracle for linear blend
    skinning (glTF 2.0 spec 3.7.3): holoray's frames 0, 5 and 9 against
    Blender's."""
    blob = bytearray()
    views, accessors, meshes = [], [], []
    add = functools.partial(add_accessor, blob, views, accessors)
    y = 0.8

    primitives = []
    for (x0, x1, mat) in ((-1.0, 0.0, 1), (0.0, 1.0, 2)):
        pos, nrm, idx = tube(x0, x1, 12, 16, 0.25, y)
        joints = [[0, 1, 0, 0]] * len(pos)
        weights = []
        for p in pos:
            w = min(1.0, max(0.0, (p[0] + 0.3) / 0.6))
            weights.append([1 - w, w, 0, 0])
        a_j = add(struct.pack("<%dB" % (4 * len(joints)), *flat(joints)), 5121, len(joints), "VEC4", 34962)
        a_w = add(struct.pack("<%df" % (4 * len(weights)), *flat(weights)), 5126, len(weights), "VEC4", 34962)
        a_idx = add(struct.pack("<%dH" % len(idx), *idx), 5123, len(idx), "SCALAR", 34963)
        attributes = {"POSITION": vec3_accessor(add, pos, True), "NORMAL": vec3_accessor(add, nrm), "JOINTS_0": a_j,
                      "WEIGHTS_0": a_w}
        primitives.append({"attributes": attributes, "indices": a_idx, "material": mat})
    meshes.append({"name": "arm", "primitives": primitives})
    meshes.append({"name": "floor", "primitives": [floor_primitive(add, 0)]})
    # Inverse bind matrices (column-major): the joints' rest frames are translations.
    ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1.0, -y, 0, 1,
           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.0, -y, 0, 1]
    a_ibm = add(struct.pack("<32f", *ibm), 5126, 2, "MAT4", None)
    views[-1].pop("target")
    times = [k / SKIN_FPS for k in range(SKIN_FRAMES)]
    a_t = add(struct.pack("<%df" % len(times), *times), 5126, len(times), "SCALAR", None,
              ([times[0]], [times[-1]]))
    views[-1].pop("target")
    shoulder = [quat_axis([0, 1, 0], math.radians(25) * k / (SKIN_FRAMES - 1)) for k in range(SKIN_FRAMES)]
    elbow = [quat_axis([0, 0, 1], math.radians(100) * k / (SKIN_FRAMES - 1)) for k in range(SKIN_FRAMES)]
    a_s = add(struct.pack("<%df" % (4 * len(shoulder)), *flat(shoulder)), 5126, len(shoulder), "VEC4", None)
    views[-1].pop("target")
    a_e = add(struct.pack("<%df" % (4 * len(elbow)), *flat(elbow)), 5126, len(elbow), "VEC4", None)
    views[-1].pop("target")
    eye = [0.5, 2.6, 4.2]
    gltf = {
        "asset": {"version": "2.0", "generator": "holoray tests/data/blender/make_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 3, 4]}],
        "nodes": [
            {"name": "arm", "mesh": 0, "skin": 0},
            {"name": "shoulder", "translation": [-1.0, y, 0.0], "children": [2]},
            {"name": "elbow", "translation": [1.0, 0.0, 0.0]},
            {"name": "floor", "mesh": 1},
            {"name": "camera", "camera": 0, "translation": eye, "rotation": look_at_quaternion(eye, [0, 0.7, 0])},
        ],
        "skins": [{"joints": [1, 2], "inverseBindMatrices": a_ibm, "skeleton": 1}],
        "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                                     {"sampler": 1, "target": {"node": 2, "path": "rotation"}}],
                        "samplers": [{"input": a_t, "output": a_s, "interpolation": "LINEAR"},
                                     {"input": a_t, "output": a_e, "interpolation": "LINEAR"}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": meshes,
        "materials": [
            material("floor", [0.5, 0.5, 0.5], 0.0, 1.0),
            material("upper", [0.9, 0.45, 0.1], 0.0, 1.0),
            material("fore", [0.1, 0.35, 0.9], 0.0, 1.0),
        ],
    }
    write_gltf(name, gltf, blob, views, accessors)


def morph_box(name):
    """A box on a grey floor with two morph targets (glTF 2.0 3.7.2.2): one
    lifts its top face by 0.8, the other slides it 0.6 along x. Over
    SKIN_FRAMES frames at SKIN_FPS the first target's weight grows from 0
    to 1 while the second's falls from 1 to 0 (one key per frame; the mesh's
    default weights are 0.5 and 0.5). The oracle for morph targets: frames
    0, 5 and 9 against Blender's."""
    blob = bytearray()
    views, accessors = [], []
    add = functools.partial(add_accessor, blob, views, accessors)

    pos, nrm, _, idx = cube(0.5)
    pos = [[p[0], p[1] + 0.5, p[2]] for p in pos]  # standing on the floor
    lift = [[0, 0.8 if p[1] > 0.9 else 0, 0] for p in pos]
    slide = [[0.6 if p[1] > 0.9 else 0, 0, 0] for p in pos]
    a_idx = add(struct.pack("<%dH" % len(idx), *idx), 5123, len(idx), "SCALAR", 34963)
    box = {"attributes": {"POSITION": vec3_accessor(add, pos, True), "NORMAL": vec3_accessor(add, nrm)},
           "indices": a_idx, "material": 1,
           "targets": [{"POSITION": vec3_accessor(add, lift, True)}, {"POSITION": vec3_accessor(add, slide, True)}]}
    floor = floor_primitive(add, 0)
    times = [k / SKIN_FPS for k in range(SKIN_FRAMES)]
    a_t = add(struct.pack("<%df" % len(times), *times), 5126, len(times), "SCALAR", None, ([times[0]], [times[-1]]))
    views[-1].pop("target")
    weights = flat([[k / (SKIN_FRAMES - 1), 1 - k / (SKIN_FRAMES - 1)] for k in range(SKIN_FRAMES)])
    a_w = add(struct.pack("<%df" % len(weights), *weights), 5126, len(weights), "SCALAR", None)
    views[-1].pop("target")
    eye = [0.6, 1.6, 4.4]
    gltf = {
        "asset": {"version": "2.0", "generator": "holoray tests/data/blender/make_scenes.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"name": "box", "mesh": 0, "rotation": [0.0, 0.2588190451, 0.0, 0.9659258263]},
            {"name": "floor", "mesh": 1},
            {"name": "camera", "camera": 0, "translation": eye, "rotation": look_at_quaternion(eye, [0, 0.8, 0])},
        ],
        "animations": [{"channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
                        "samplers": [{"input": a_t, "output": a_w, "interpolation": "LINEAR"}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": [{"name": "box", "primitives": [box], "weights": [0.5, 0.5]}, {"name": "floor", "primitives": [floor]}],
        "materials": [
            material("floor", [0.5, 0.5, 0.5], 0.0, 1.0),
            material("box", [0.2, 0.7, 0.3], 0.0, 1.0),
        ],
    }
    write_gltf(name, gltf, blob, views, accessors)


def mapped_plane(name):
    """A square under a sun, its glTF metallicRoughnessTexture and
    normalTexture both varying: the top half of the image metal (blue 255),
    the bottom dielectric (blue 0); roughness (green) 0.3 on the left, 0.7 on
    the right; the normal map tilting the normal along u by 0.6 cos(8 pi u)
    and along the image's up by 0.4 sin(6 pi y / size) (RGB = (n + 1) / 2),
    so that both tangent directions show. The oracle for the
    texture-driven BRDF inputs and the tangent frame: direct light and albedo
    against Blender's."""
    size = 64
    normal, mr = [], []
    for y in range(size):
        for x in range(size):
            u = (x + 0.5) / size
            up = 1 - (y + 0.5) / size  # rows run down the image
            n = [-0.6 * math.cos(8 * math.pi * u), -0.4 * math.sin(6 * math.pi * up), 1.0]
            length = math.sqrt(sum(c * c for c in n))
            normal.append(tuple(int(round(255 * (c / length + 1) / 2)) for c in n))
            mr.append((0, 77 if x < size // 2 else 179, 255 if y < size // 2 else 0))
    write_png(os.path.join(HERE, name + "_normal.png"), size, size, normal)
    write_png(os.path.join(HERE, name + "_mr.png"), size, size, mr)
    blob = bytearray()
    views, accessors = [], []
    add = functools.partial(add_accessor, blob, views, accessors)
    pos = [[-1, 0, 1], [1, 0, 1], [1, 0, -1], [-1, 0, -1]]
    nrm = [[0, 1, 0]] * 4
    uv = [[0, 1], [1, 1], [1, 0], [0, 0]]  # glTF's v runs down the image: the far edge (z = -1) is the image's top
    a_pos = add(struct.pack("<12f", *flat(pos)), 5126, 4, "VEC3", 34962, ([-1, 0, -1], [1, 0, 1]))
    a_nrm = add(struct.pack("<12f", *flat(nrm)), 5126, 4, "VEC3", 34962)
    a_uv = add(struct.pack("<8f", *flat(uv)), 5126, 4, "VEC2", 34962)
    a_idx = add(struct.pack("<6H", 0, 1, 2, 0, 2, 3), 5123, 6, "SCALAR", 34963)
    eye = [0.0, 2.4, 2.6]
    sun_dir = [0.5, -1.0, -0.6]
    gltf = {
        "asset": {"version": "2.0", "generator": "holoray tests/data/blender/make_scenes.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 900.0}]}},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [
            {"mesh": 0},
            {"camera": 0, "translation": eye, "rotation": look_at_quaternion(eye, [0, 0, 0])},
            {"name": "sun", "rotation": look_at_quaternion([0, 0, 0], sun_dir),
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1.0, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": a_pos, "NORMAL": a_nrm, "TEXCOORD_0": a_uv},
                                    "indices": a_idx, "material": 0}]}],
        "materials": [{"name": "mapped",
                       "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1], "metallicFactor": 1.0,
                                                "roughnessFactor": 1.0, "metallicRoughnessTexture": {"index": 1}},
                       "normalTexture": {"index": 0, "scale": 1.0}}],
        "textures": [{"sampler": 0, "source": 0}, {"sampler": 0, "source": 1}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729, "wrapS": 33071, "wrapT": 33071}],
        "images": [{"uri": name + "_normal.png"}, {"uri": name + "_mr.png"}],
    }
    write_gltf(name, gltf, blob, views, accessors)


if __name__ == "__main__":
    embedded_copies("textured_box", *textured_box("textured_box"))
    # UVs over [0, 2]: the image repeats twice per face one way and mirrors the other.
    textured_box("wrapped_box", wrap_s=10497, wrap_t=33648, uv_scale=2.0)
    # KHR_texture_transform: offset, rotation and a non-uniform scale, repeated.
    textured_box("transform_box", transform={"offset": [0.2, 0.1], "rotation": 0.4, "scale": [1.5, 0.8]})
    masked_leaf("masked_leaf")
    lit_spheres("lit_spheres")
    skinned_arm("skinned_arm")
    morph_box("morph_box")
    mapped_plane("mapped_plane")
