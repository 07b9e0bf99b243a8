"""The add-on as a Blender extension (Blender 4.2 and later): the zip the
build packs with `blender --command extension build` passes Blender's own
validation, installs from the file into a fresh user folder, and renders an
EIA there, with nothing else of holoray's on Blender's add-on paths.
Skipped with Blender 3.4 (Debian 12), which loads the add-on itself
(test_addon.py)."""

import os
import re
import shutil
import subprocess

import pytest

import holoray

HERE = os.path.dirname(os.path.abspath(__file__))
BLENDER = shutil.which("blender")
EXTENSION = os.environ.get("HOLORAY_BLENDER_EXTENSION", "")
MODULE = "bl_ext.user_default.holoray_blender"  # an extension's module in the user's own repository


def blender_version():
    if BLENDER is None:
        return None
    out = subprocess.run([BLENDER, "--version"], capture_output=True, text=True, timeout=120).stdout
    m = re.search(r"Blender (\d+)\.(\d+)", out)
    return (int(m.group(1)), int(m.group(2))) if m else None


pytestmark = pytest.mark.skipif((blender_version() or (0, 0)) < (4, 2),
                                reason="extensions need Blender 4.2 or later (Debian 12's 3.4 takes the add-on)")


def user_env(user_dir):
    """A fresh Blender user folder, without the build's add-on folder on its paths."""
    e = {k: v for k, v in os.environ.items() if not k.startswith("BLENDER_USER_")}
    e["BLENDER_USER_RESOURCES"] = str(user_dir)
    e["PATH"] = os.pathsep.join([os.path.dirname(os.path.abspath(os.environ["HOLORAY_CLI"])), e.get("PATH", "")])
    return e


def run(args, env, timeout=300):
    r = subprocess.run([BLENDER] + args, env=env, capture_output=True, text=True, timeout=timeout)
    return r.returncode, r.stdout + r.stderr


def test_the_build_made_the_extension_zip():
    assert EXTENSION.endswith(".zip") and os.path.isfile(EXTENSION), EXTENSION


def test_blender_validates_the_extension_zip():
    code, log = run(["--factory-startup", "--command", "extension", "validate", EXTENSION], dict(os.environ))
    assert code == 0, log[-3000:]
    assert "Success" in log, log[-3000:]


def test_blender_installs_the_extension_from_the_zip_and_renders_with_it(tmp_path):
    env = user_env(tmp_path / "user")
    code, log = run(["--factory-startup", "--command", "extension", "install-file", "--repo", "user_default",
                     "--enable", EXTENSION], env)
    assert code == 0, log[-3000:]
    installed = list((tmp_path / "user").rglob("holoray_blender/blender_manifest.toml"))
    assert installed, f"nothing installed under {tmp_path / 'user'}:\n{log[-3000:]}"

    # The tests' scene with the installed extension as its engine, saved, then
    # rendered as a user does: no --addons, the preferences enable it.
    env_scene = dict(env, HOLORAY_BLENDER_ADDON=MODULE)
    scene_run = subprocess.run([BLENDER, "-b", "--factory-startup", "--python", os.path.join(HERE, "case.py"), "--",
                                "eia", str(tmp_path)], env=env_scene, capture_output=True, text=True, timeout=300)
    assert scene_run.returncode == 0 and "RESULT " in scene_run.stdout, scene_run.stdout[-3000:] + scene_run.stderr[-3000:]
    code, log = run(["-b", str(tmp_path / "scene.blend"), "-E", "HOLORAY", "-o", str(tmp_path / "frame_####"),
                     "-F", "OPEN_EXR", "-f", "1"], env)
    assert "Error" not in log and "Traceback" not in log, log[-3000:]
    frame = holoray.read_image(tmp_path / "frame_0001.exr")
    assert frame.shape[:2] == (80, 120), log[-3000:]  # 24x16 lenses x 5 px
    assert frame[:, :, :3].max() > 0.05, "the EIA is black"
