"""Fixtures of the Python module's tests.

Run from the repository root:

    PYTHONPATH=build/python HOLORAY_CLI=build/holoray /usr/bin/python3 -m pytest tests/python -q

The CLI (`holoray`) is the reference the module is compared with; HOLORAY_CLI
names it (default: <repo>/build/holoray).
"""
from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]

# The same thread count on both sides of every comparison (the images do
# not depend on it, but the comparison should not rely on that).
THREADS = 2


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    """The repository root."""
    return REPO


@pytest.fixture(scope="session")
def cli() -> pathlib.Path:
    """The `holoray` executable: $HOLORAY_CLI, else <repo>/build/holoray."""
    path = pathlib.Path(os.environ.get("HOLORAY_CLI", REPO / "build" / "holoray"))
    if not path.is_absolute():
        path = (pathlib.Path.cwd() / path).resolve()
    if not (path.is_file() and os.access(path, os.X_OK)):
        pytest.fail(f"the holoray CLI is not at {path} (set HOLORAY_CLI)")
    return path


@pytest.fixture
def tmp(tmp_path: pathlib.Path) -> pathlib.Path:
    """A fresh empty folder for one test."""
    return tmp_path


@pytest.fixture(scope="session")
def run_cli(cli):
    """run_cli(*args, cwd=None, ok=True) runs `holoray args...` and returns the
    CompletedProcess (text); with ok, a non-zero exit status fails the test
    with the command's output."""

    def run(*args, cwd=None, ok=True, timeout=300):
        cmd = [str(cli), *map(str, args)]
        proc = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout)
        if ok and proc.returncode != 0:
            pytest.fail(f"{' '.join(cmd)} exited {proc.returncode}\nstdout:\n{proc.stdout}\nstderr:\n{proc.stderr}")
        return proc

    return run


@pytest.fixture(scope="session")
def primitives_path() -> pathlib.Path:
    """examples/primitives.nff: every NFF primitive, a mirror, glass, 2 lights, a viewpoint."""
    return REPO / "examples" / "primitives.nff"


@pytest.fixture(scope="session")
def primitives(primitives_path):
    """The loaded primitives scene, shared (a Scene is rendered any number of times)."""
    import holoray

    return holoray.load_scene(str(primitives_path))


@pytest.fixture(scope="session")
def python_env() -> dict:
    """The environment for a child /usr/bin/python3 that imports holoray as this one does."""
    import holoray

    env = dict(os.environ)
    package_parent = str(pathlib.Path(holoray.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join([package_parent, *filter(None, [env.get("PYTHONPATH")])])
    return env

