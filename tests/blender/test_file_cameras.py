"""File cameras as Blender frames them (issue 53): for sample files of every
format holoray reads that carries cameras and that Blender imports (Collada,
FBX, .blend, glTF), holoray's view through the file's camera must cover the
pixels Blender's import of the same file covers: silhouettes (holoray's id
AOV, Blender's alpha from Cycles with one sample at each pixel's centre)
with an intersection over union of at least 0.98. Blender renders the image
at the size the test gives, so the field of view, the axis it spans and the
aspect are all checked. Skipped where Blender or Debian's assimp-testmodels
is missing."""

import json
import os
import shutil
import subprocess

import numpy as np
import pytest

import holoray

HERE = os.path.dirname(os.path.abspath(__file__))
BLENDER = shutil.which("blender")
MODELS = "/usr/share/assimp/models"
pytestmark = [pytest.mark.skipif(BLENDER is None, reason="Blender is not installed"),
              pytest.mark.skipif(not os.path.isdir(MODELS), reason="assimp-testmodels is not installed")]

# (file, width, height, holoray's camera name, Blender's): sizes at the
# file's aspect and, for some, another one (the axis the angle spans). Left
# out: files whose camera shows Blender nothing (spider.fbx, huesitos.fbx and
# test_279.blend put the eye inside or far from a model its clipping range
# cuts away; holoray does not clip), and skinned models (posed differently).
CASES = [
    ("Collada/duck.dae", 240, 160, "", ""),                  # yfov with aspect_ratio
    ("Collada/duck.dae", 160, 160, "", ""),
    ("Collada/COLLADA.dae", 200, 200, "testCamera", "testCamera"),  # the second of two cameras
    ("BLEND/BlenderDefault_276.blend", 256, 144, "", ""),   # sensor fit auto: the larger side
    ("BLEND/BlenderDefault_276.blend", 144, 256, "", ""),
    ("BLEND/AreaLight_269.blend", 256, 144, "", ""),
    ("FBX/global_settings.fbx", 256, 144, "", ""),          # FieldOfView, horizontal
    ("FBX/global_settings.fbx", 144, 144, "", ""),
    ("glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 240, 160, "", ""),  # yfov: vertical
    ("glTF2/cameras/Cameras.gltf", 240, 160, "", ""),
    ("glTF2/cameras/Cameras.gltf", 200, 200, "nodes[2]", "Camera.001"),  # orthographic
]


def blender_mask(path, width, height, camera, tmp_path):
    out = str(tmp_path / "blender.png")
    run = subprocess.run([BLENDER, "-b", "--factory-startup", "--python", os.path.join(HERE, "file_camera.py"), "--",
                          path, str(width), str(height), out, camera], capture_output=True, text=True, timeout=300)
    if run.returncode == 0 and "\nSKIP " in "\n" + run.stdout:
        pytest.skip(run.stdout.split("SKIP ", 1)[1].splitlines()[0])
    lines = [l for l in run.stdout.splitlines() if l.startswith("RESULT ")]
    assert run.returncode == 0 and lines, run.stdout[-3000:] + run.stderr[-3000:]
    return holoray.read_image(out)[:, :, 3] > 0.5, json.loads(lines[-1][len("RESULT "):])


def holoray_mask(path, width, height, camera):
    scene = holoray.load_scene(path, camera_name=camera)
    result = holoray.render(scene, holoray.Pinhole((width, height)), aovs=["id"])
    return result.aovs["id"] >= 0


@pytest.mark.parametrize("name,width,height,camera,blender_camera", CASES,
                         ids=[f"{c[0].split('/')[-1]}-{c[1]}x{c[2]}{'-' + c[3] if c[3] else ''}" for c in CASES])
def test_file_camera_frames_the_model_as_blender_does(name, width, height, camera, blender_camera, tmp_path):
    path = os.path.join(MODELS, name)
    theirs, info = blender_mask(path, width, height, blender_camera, tmp_path)
    ours = holoray_mask(path, width, height, camera)
    union = np.logical_or(ours, theirs).sum()
    iou = np.logical_and(ours, theirs).sum() / union
    assert theirs.sum() > 0.01 * theirs.size, f"Blender's view of {name} is nearly empty: {info}"
    assert iou >= 0.98, f"{name} {width}x{height}: IoU {iou:.4f}; ours {ours.sum()} px, Blender's {theirs.sum()} px ({info})"


def test_clipping_hides_what_blender_hides(tmp_path):
    # COLLADA.dae's first camera starts seeing 10 units out, past its model:
    # Blender shows nothing, and neither does holoray's view through it.
    path = os.path.join(MODELS, "Collada/COLLADA.dae")
    theirs, info = blender_mask(path, 120, 120, "", tmp_path)
    assert info["clip"][0] == pytest.approx(10)
    scene = holoray.load_scene(path)
    result = holoray.render(scene, holoray.Pinhole((120, 120)), aovs=["id"])
    assert "sees 10 to 1000 along its axis (the file's clipping)" in result.description
    assert theirs.sum() == 0 and (result.aovs["id"] >= 0).sum() == 0
