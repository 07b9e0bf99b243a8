"""Scenes built from numpy arrays render as the same geometry read from files.

The meshes have integer coordinates so that every reader (assimp's OBJ
parser, NFF's) gets exactly the float the array holds; colours are dyadic
fractions with short decimals for the same reason.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import holoray
from conftest import THREADS
from helpers import srgb_decode, write_image

TERRAIN_COLOUR = (0.25, 0.5, 0.75)
CUBE_COLOUR = (0.875, 0.125, 0.375)
VIEW = dict(eye=(7.0, -10.0, 9.0), at=(0.0, 0.0, 1.0), up=(0.0, 0.0, 1.0), fov_deg=45.0)


def terrain():
    """A wavy 9x9 grid over [-4, 4]^2 with integer heights; faces CCW seen from +z."""
    xs = np.arange(-4, 5)
    vertices = np.array([(x, y, round(1.5 * math.sin(0.9 * x) * math.cos(0.7 * y))) for y in xs for x in xs],
                        dtype=np.float64)
    n = len(xs)
    faces = []
    for j in range(n - 1):
        for i in range(n - 1):
            v00, v10, v01, v11 = j * n + i, j * n + i + 1, (j + 1) * n + i, (j + 1) * n + i + 1
            faces += [(v00, v10, v11), (v00, v11, v01)]
    return vertices, np.array(faces, dtype=np.int64)


def cube(lo=(0, -2, 2), hi=(2, 0, 4)):
    """An axis-aligned box with integer corners; 12 triangles CCW seen from outside."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    vertices = np.array([(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)], dtype=np.float64)
    # 0:(x0,y0,z0) 1:(x1,y0,z0) 2:(x0,y1,z0) 3:(x1,y1,z0) 4..7 the same at z1
    quads = [(0, 2, 3, 1),  # bottom, -z
             (4, 5, 7, 6),  # top, +z
             (0, 1, 5, 4),  # front, -y
             (2, 6, 7, 3),  # back, +y
             (0, 4, 6, 2),  # left, -x
             (1, 3, 7, 5)]  # right, +x
    faces = []
    for a, b, c, d in quads:
        faces += [(a, b, c), (a, c, d)]
    return vertices, np.array(faces, dtype=np.int64)


def check_winding(vertices, faces, centre):
    """Every face's normal points away from centre (a test of the test's meshes)."""
    v = vertices[faces]
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    assert (np.einsum("ij,ij->i", n, v.mean(axis=1) - centre) > 0).all()


def write_obj(path, parts):
    """parts: [(name, vertices, faces, colour)] -> an OBJ and its MTL, one object and material each."""
    mtl = path.with_suffix(".mtl")
    lines = [f"mtllib {mtl.name}"]
    mtl_lines = []
    base = 1
    for name, vertices, faces, colour in parts:
        lines.append(f"o {name}")
        lines += [f"v {int(x)} {int(y)} {int(z)}" for x, y, z in vertices]
        lines.append(f"usemtl m_{name}")
        lines += [f"f {a + base} {b + base} {c + base}" for a, b, c in faces]
        base += len(vertices)
        mtl_lines += [f"newmtl m_{name}", "Kd {} {} {}".format(*colour), "Ka 0 0 0", "Ks 0 0 0", ""]
    path.write_text("\n".join(lines) + "\n")
    mtl.write_text("\n".join(mtl_lines))


def numpy_scene(**mesh_kwargs):
    scene = holoray.Scene()
    tv, tf = terrain()
    cv, cf = cube()
    ids = (scene.add_mesh(tv, tf, colour=TERRAIN_COLOUR, **mesh_kwargs),
           scene.add_mesh(cv, cf, colour=CUBE_COLOUR, **mesh_kwargs))
    scene.set_viewpoint(**VIEW)
    return scene, ids


CAMERAS = {
    "lens_array": lambda: holoray.LensArray(lenses=(24, 24), pixels_per_lens=4),
    "lens_array_hex": lambda: holoray.LensArray(lenses=(20, 20), pixels_per_lens=4, grid="hex"),
    "pinhole": lambda: holoray.Pinhole(resolution=(64, 48)),
}


def test_test_meshes_face_outward():
    v, f = cube()
    check_winding(v, f, np.array([1.0, -1.0, 3.0]))
    v, f = terrain()
    t = v[f]
    assert (np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])[:, 2] > 0).all()


@pytest.mark.parametrize("camera", list(CAMERAS))
def test_numpy_mesh_renders_the_depth_and_albedo_of_the_same_obj(tmp, camera):
    scene, _ = numpy_scene()
    tv, tf = terrain()
    cv, cf = cube()
    write_obj(tmp / "m.obj", [("terrain", tv, tf, TERRAIN_COLOUR), ("cube", cv, cf, CUBE_COLOUR)])
    loaded = holoray.load_scene(tmp / "m.obj")
    loaded.set_viewpoint(**VIEW)
    assert loaded.object_count == scene.object_count == 2

    a = holoray.render(scene, CAMERAS[camera](), threads=THREADS, aovs=("albedo", "depth"))
    b = holoray.render(loaded, CAMERAS[camera](), threads=THREADS, aovs=("albedo", "depth"))
    depth = a.aovs["depth"]
    hit = np.isfinite(depth)
    assert 0.05 < hit.mean() < 0.99, f"the view should show the meshes and some background ({hit.mean():.2f} hit)"
    np.testing.assert_array_equal(depth, b.aovs["depth"])
    np.testing.assert_array_equal(a.aovs["albedo"], b.aovs["albedo"])
    # Both objects are seen, each with its own flat colour.
    albedo = a.aovs["albedo"][hit]
    for colour in (TERRAIN_COLOUR, CUBE_COLOUR):
        assert (albedo == np.float32(colour)).all(axis=1).any(), f"no pixel of colour {colour}"


def test_add_mesh_returns_the_id_the_id_aov_shows():
    scene, (terrain_id, cube_id) = numpy_scene()
    assert terrain_id != cube_id
    result = holoray.render(scene, holoray.LensArray(lenses=(24, 24), pixels_per_lens=4), threads=THREADS,
                            aovs=("albedo", "depth", "id"))
    ids, albedo = result.aovs["id"], result.aovs["albedo"]
    assert set(np.unique(ids)) == {-1, terrain_id, cube_id}
    np.testing.assert_array_equal(ids == -1, np.isnan(result.aovs["depth"]))
    assert (albedo[ids == terrain_id] == np.float32(TERRAIN_COLOUR)).all()
    assert (albedo[ids == cube_id] == np.float32(CUBE_COLOUR)).all()


def test_add_sphere_renders_the_depth_and_albedo_of_the_same_nff_sphere(tmp):
    nff = tmp / "s.nff"
    nff.write_text("v\nfrom 0 -10 4\nat 0 0 1\nup 0 0 1\nangle 40\nhither 0.01\nresolution 64 64\n"
                   "b 0 0 0\nl 3 -6 9\n"
                   "f 0.25 0.5 0.75 1 0 0 0 1\ns 0 0 1 2\n"
                   "f 0.875 0.125 0.375 1 0 0 0 1\ns 3 2 0 1\n")
    loaded = holoray.load_scene(nff)
    scene = holoray.Scene()
    first = scene.add_sphere((0, 0, 1), 2, colour=(0.25, 0.5, 0.75))
    second = scene.add_sphere((3.0, 2.0, 0.0), 1.0, colour=(0.875, 0.125, 0.375))
    assert first != second
    scene.add_light((3, -6, 9))
    scene.set_viewpoint((0, -10, 4), (0, 0, 1), (0, 0, 1), 40)
    assert scene.object_count == loaded.object_count == 2
    assert scene.light_count == loaded.light_count == 1
    for camera in (holoray.LensArray(lenses=(16, 16), pixels_per_lens=4), holoray.Pinhole(resolution=(40, 30))):
        a = holoray.render(scene, camera, threads=THREADS, aovs=("albedo", "depth", "id"))
        b = holoray.render(loaded, camera, threads=THREADS, aovs=("albedo", "depth", "id"))
        assert np.isfinite(a.aovs["depth"]).any()
        np.testing.assert_array_equal(a.aovs["depth"], b.aovs["depth"])
        np.testing.assert_array_equal(a.aovs["albedo"], b.aovs["albedo"])
        assert set(np.unique(a.aovs["id"])) == {-1, first, second}


def test_counts_follow_what_was_added():
    scene = holoray.Scene()
    assert scene.object_count == 0 and scene.light_count == 0
    v, f = cube()
    scene.add_mesh(v, f)
    scene.add_sphere((5, 5, 5), 1)
    scene.add_light((0, 0, 10))
    scene.add_light((0, 10, 10), (0.5, 0.5, 0.5))
    assert scene.object_count == 2
    assert scene.light_count == 2
    assert isinstance(scene.warnings, list)


def _render_mesh(vertices, faces, **kwargs):
    scene = holoray.Scene()
    scene.add_mesh(vertices, faces, colour=TERRAIN_COLOUR, **kwargs)
    scene.set_viewpoint(**VIEW)
    r = holoray.render(scene, holoray.LensArray(lenses=(16, 16), pixels_per_lens=4), threads=THREADS,
                       aovs=("depth", "normal", "albedo"))
    return r


def _assert_same_render(a, b):
    np.testing.assert_array_equal(a.colour, b.colour)
    for aov in ("depth", "normal", "albedo"):
        np.testing.assert_array_equal(a.aovs[aov], b.aovs[aov])


@pytest.fixture(scope="module")
def contiguous_render():
    v, f = terrain()
    r = _render_mesh(np.ascontiguousarray(v), np.ascontiguousarray(f))
    assert np.isfinite(r.aovs["depth"]).any()
    return r


def test_strided_vertices_render_as_their_contiguous_copy(contiguous_render):
    v, f = terrain()
    bigger = np.zeros((2 * len(v), 3))
    bigger[::2] = v
    bigger[1::2] = 1e30  # would show if the odd rows were read
    strided = bigger[::2]
    assert not strided.flags.c_contiguous
    _assert_same_render(_render_mesh(strided, f), contiguous_render)


def test_strided_faces_render_as_their_contiguous_copy(contiguous_render):
    v, f = terrain()
    bigger = np.full((len(f), 6), 10**6, dtype=np.int64)
    bigger[:, ::2] = f
    strided = bigger[:, ::2]
    assert not strided.flags.c_contiguous
    _assert_same_render(_render_mesh(v, strided), contiguous_render)


def test_fortran_ordered_arrays_render_as_their_contiguous_copies(contiguous_render):
    v, f = terrain()
    fv, ff = np.asfortranarray(v), np.asfortranarray(f)
    assert not fv.flags.c_contiguous and not ff.flags.c_contiguous
    _assert_same_render(_render_mesh(fv, ff), contiguous_render)


@pytest.mark.parametrize("vdtype", [np.float32, np.float64])
@pytest.mark.parametrize("fdtype", [np.int32, np.int64, np.uint32, np.uint64])
def test_vertex_and_index_dtypes_render_the_same(contiguous_render, vdtype, fdtype):
    v, f = terrain()  # integer-valued: exact in every dtype
    _assert_same_render(_render_mesh(v.astype(vdtype), f.astype(fdtype)), contiguous_render)


def test_nested_lists_render_as_arrays(contiguous_render):
    v, f = terrain()
    _assert_same_render(_render_mesh(v.tolist(), f.tolist()), contiguous_render)


def _quad(normals=None, uv=None, texture=None, colour=(1.0, 1.0, 1.0)):
    """A 4x4 square in z = 0 seen from straight above."""
    vertices = np.array([(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)], dtype=np.float64)
    faces = np.array([(0, 1, 2), (0, 2, 3)])
    scene = holoray.Scene()
    scene.add_mesh(vertices, faces, normals=normals, uv=uv, texture=texture, colour=colour)
    scene.set_viewpoint((0, 0, 10), (0, 0, 0), (0, 1, 0), 30)
    result = holoray.render(scene, holoray.Pinhole(resolution=(32, 32)), threads=THREADS,
                            aovs=("albedo", "normal", "depth"))
    hit = np.isfinite(result.aovs["depth"])
    assert hit.sum() > 100
    return result, hit


def test_flat_shading_normal_is_the_face_normal():
    result, hit = _quad()
    np.testing.assert_allclose(result.aovs["normal"][hit], np.broadcast_to([0, 0, 1], (hit.sum(), 3)), atol=1e-6)


def test_given_vertex_normals_are_the_shading_normal():
    n = np.array([0.6, 0.0, 0.8])
    result, hit = _quad(normals=np.tile(n, (4, 1)))
    np.testing.assert_allclose(result.aovs["normal"][hit], np.broadcast_to(n, (hit.sum(), 3)), atol=1e-6)


UV = np.array([(0, 0), (1, 0), (1, 1), (0, 1)], dtype=np.float64)


def test_uint8_texture_is_srgb_decoded_and_multiplies_the_colour():
    code = np.array([200, 128, 30], dtype=np.uint8)
    texture = np.broadcast_to(code, (8, 8, 3)).copy()
    colour = (0.5, 1.0, 0.75)
    result, hit = _quad(uv=UV, texture=texture, colour=colour)
    expected = np.array(colour) * srgb_decode(code / 255.0)
    np.testing.assert_allclose(result.aovs["albedo"][hit], np.broadcast_to(expected, (hit.sum(), 3)), atol=2e-6)


def test_float_texture_is_linear_and_multiplies_the_colour():
    value = np.array([0.25, 0.5, 1.0], dtype=np.float32)
    colour = (0.5, 1.0, 0.75)
    for texture in (np.broadcast_to(value, (8, 8, 3)).copy(),
                    np.concatenate([np.broadcast_to(value, (8, 8, 3)), np.ones((8, 8, 1), np.float32)], axis=2)):
        result, hit = _quad(uv=UV, texture=texture, colour=colour)
        expected = np.array(colour) * value
        # Tolerance: texels may be stored as 8-bit sRGB codes (half a code is
        # under 0.003 in linear at these values); read as sRGB instead of
        # linear, 0.5 would come out 0.21.
        np.testing.assert_allclose(result.aovs["albedo"][hit], np.broadcast_to(expected, (hit.sum(), 3)), atol=0.004)


def test_texture_v_runs_up_from_the_bottom_row():
    # Top half of the image red, bottom half blue; the quad's v = 1 edge is at
    # +y, the top of the pinhole view (up +y).
    texture = np.zeros((8, 8, 3), np.float32)
    texture[:4] = (1, 0, 0)
    texture[4:] = (0, 0, 1)
    result, hit = _quad(uv=UV, texture=texture)
    albedo = result.aovs["albedo"]
    rows = np.nonzero(hit.any(axis=1))[0]
    # A quarter of the way in from each edge: texels there are not blended
    # with the opposite edge's (the texture repeats, and is filtered).
    quarter = (rows[-1] - rows[0]) // 4
    top, bottom = rows[0] + quarter, rows[-1] - quarter
    cols = np.nonzero(hit[top])[0]
    middle = cols[len(cols) // 2]
    assert albedo[top, middle, 0] > 0.9 and albedo[top, middle, 2] < 0.1, albedo[top, middle]
    assert albedo[bottom, middle, 2] > 0.9 and albedo[bottom, middle, 0] < 0.1, albedo[bottom, middle]


def test_numpy_texture_renders_as_the_same_texture_of_an_obj_file(tmp):
    # A random 8-bit texture: as uint8 sRGB codes through add_mesh, and as a
    # PNG of the same codes through an MTL's map_Kd (sRGB-decoded too). Any
    # flip or transpose of the array shows.
    rng = np.random.default_rng(5)
    codes = rng.integers(0, 256, (6, 5, 3), dtype=np.uint8)
    write_image(tmp / "t.png", codes / np.float32(255))
    (tmp / "q.mtl").write_text("newmtl a\nKd 1 1 1\nKa 0 0 0\nKs 0 0 0\nmap_Kd t.png\n")
    (tmp / "q.obj").write_text("mtllib q.mtl\nv -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
    loaded = holoray.load_scene(tmp / "q.obj")
    loaded.set_viewpoint((0, 0, 10), (0, 0, 0), (0, 1, 0), 30)
    from_file = holoray.render(loaded, holoray.Pinhole(resolution=(32, 32)), threads=THREADS,
                               aovs=("albedo", "depth"))
    from_array, hit = _quad(uv=UV, texture=codes)
    np.testing.assert_array_equal(np.isfinite(from_file.aovs["depth"]), hit)
    np.testing.assert_allclose(from_array.aovs["albedo"], from_file.aovs["albedo"], atol=1e-6)


def test_a_scene_without_lights_is_lit_by_a_headlight():
    result, hit = _quad()
    assert (result.colour[hit] > 0.05).all()
