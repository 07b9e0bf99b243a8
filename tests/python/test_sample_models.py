"""A model's EIA shows the model without any placement option (issue 53): for
a sample file of every format holoray reads through assimp (Debian's
assimp-testmodels), the EIA's centre sub-aperture view (the pixel at the
centre of every lens) must neither miss the model nor be filled by it. Files
with cameras place the array at the depth of the scene's centre along the
file camera's view; files without, by the three-quarter view framing the
scene. Skipped where assimp-testmodels is missing."""

import os

import numpy as np
import pytest

import holoray

MODELS = "/usr/share/assimp/models"
pytestmark = pytest.mark.skipif(not os.path.isdir(MODELS), reason="assimp-testmodels is not installed")

# One file per format (extension), those with a camera of their own marked.
SAMPLES = [
    "3DS/fels.3ds", "3DS/CameraRollAnim.3ds",            # camera (keyframed: its target aimed at the scene)
    "3MF/box.3mf", "AC/Wuson.ac", "AMF/test1.amf",
    "ASE/CameraRollAnim.ase",                            # camera
    "B3D/WusonBlitz.b3d",
    "BLEND/BlenderDefault_276.blend",                    # camera
    "COB/spider_4_3.cob",
    "Collada/duck.dae",                                  # camera
    "DXF/wuson.dxf",
    "FBX/global_settings.fbx",                           # camera
    "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
    "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",  # camera, 1000 units across
    "HMP/terrain.hmp", "IQM/mrfixit.iqm", "LWO/LWO2/hierarchy.lwo",
    "LWS/move_x.lws",                                    # camera
    "MD2/faerie.md2", "MD5/SimpleCube.md5mesh", "MS3D/jeep1.ms3d",
    "OBJ/spider.obj", "OFF/Wuson.off",
    "OpenGEX/camera.ogex",                               # camera
    "PLY/cube.ply", "Q3D/earth.q3o", "SIB/heffalump.sib", "SMD/triangle.smd", "STL/Spider_binary.stl",
    "X/test.x", "X3D/ComputerKeyboard.x3d", "XGL/sample_official.xgl",
]

LENSES, P = 24, 5


@pytest.mark.parametrize("name", SAMPLES)
def test_centre_view_of_the_eia_shows_the_model(name):
    path = os.path.join(MODELS, name)
    if not os.path.isfile(path):
        pytest.skip(f"{name} is not in this assimp-testmodels")
    scene = holoray.load_scene(path)
    result = holoray.render(scene, holoray.LensArray((LENSES, LENSES), P), aovs=["id"])
    centre = result.aovs["id"][P // 2::P, P // 2::P]  # one pixel per lens: the centre sub-aperture view
    covered = float((centre >= 0).mean())
    assert 0.01 <= covered <= 0.95, f"{name}: the model covers {covered:.3f} of the centre view\n{result.description}"


def test_texture_path_finds_another_machines_textures():
    spider = os.path.join(MODELS, "FBX/spider.fbx")
    assert any("drkwood2.jpg" in w for w in holoray.load_scene(spider).warnings)
    found = holoray.load_scene(spider, texture_path=os.path.join(MODELS, "OBJ"))
    assert not [w for w in found.warnings if "texture" in w]


def test_an_unknown_camera_name_is_a_value_error_naming_the_cameras():
    path = os.path.join(MODELS, "Collada/COLLADA.dae")
    second = holoray.load_scene(path, camera_name="testCamera")
    result = holoray.render(second, holoray.Pinhole((32, 32)))
    assert result.description.startswith("camera     'testCamera' from the file, 37.85 deg horizontal; sees 0.01 to 1000")
    with pytest.raises(ValueError, match=r"has no camera 'nope' \(its cameras: 'Camera', 'testCamera'\)"):
        holoray.load_scene(path, camera_name="nope")


def test_focus_distance_moves_a_file_cameras_lens_array():
    duck = holoray.load_scene(os.path.join(MODELS, "Collada/duck.dae"))
    at_centre = holoray.render(duck, holoray.LensArray((16, 16), 4)).description
    at_three = holoray.render(duck, holoray.LensArray((16, 16), 4, focus_distance=3.0)).description
    assert "focal plane 6.85342 from the eye (the depth of the scene's centre)" in at_centre
    assert "focal plane 3 from the eye (focus distance given)" in at_three
    # The array spans the camera's field where it stands: 2 d tan(54.43 / 2) over 16 lenses.
    assert "pitch 0.192857," in at_three


def test_centre_view_shows_the_whole_duck_and_a_far_focus_the_whole_engine():
    # The duck's camera frames all of it: so does the EIA's centre view, no
    # pixel of its border on the duck. The engine's camera is a close-up (its
    # own view cuts the engine): a focal plane farther out shows it whole.
    def view(name, **kw):
        scene = holoray.load_scene(os.path.join(MODELS, name))
        result = holoray.render(scene, holoray.LensArray((48, 48), 5, **kw), aovs=["id"])
        return result.aovs["id"][2::5, 2::5] >= 0
    def whole(v):
        border = np.concatenate([v[0], v[-1], v[:, 0], v[:, -1]])
        return v.mean() > 0.01 and not border.any()
    engine = "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
    assert whole(view("Collada/duck.dae"))
    assert not whole(view(engine))
    assert whole(view(engine, focus_distance=3000.0))
