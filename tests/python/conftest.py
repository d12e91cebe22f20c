"""Shared fixtures of the Python suite (run by ctest as python.module).

The module under test is the one on PYTHONPATH (ctest points it at the build tree). GraspIt!'s
corpus is found at ../shared beside the project checkout, or where GRASPKIT_SHARED says; where it
is absent the tests that need it say so loudly and are skipped, and ctest reports the run as
skipped, not passed.
"""

import json
import os
import pathlib
import shutil
import subprocess

import pytest

PROJECT = pathlib.Path(__file__).resolve().parents[2]


def shared_dir():
    return pathlib.Path(os.environ.get("GRASPKIT_SHARED", PROJECT.parent / "shared"))


@pytest.fixture(scope="session")
def shared():
    folder = shared_dir()
    if not (folder / "graspit-data").is_dir():
        pytest.skip(f"graspkit: SKIPPED: the shared GraspIt! corpus is not at {folder} "
                    "(set GRASPKIT_SHARED)")
    return folder


@pytest.fixture(scope="session")
def graspit_data(shared):
    return shared / "graspit-data"


@pytest.fixture(scope="session")
def reference(shared):
    with open(shared / "reference" / "graspit-figures.json") as f:
        return json.load(f)


@pytest.fixture(scope="session")
def models():
    return PROJECT / "models"


@pytest.fixture(scope="session")
def graspkit_exe():
    """The command-line program of the same build (GRASPKIT_EXE), for comparisons."""
    exe = os.environ.get("GRASPKIT_EXE") or shutil.which("graspkit")
    if not exe:
        pytest.fail("GRASPKIT_EXE is not set and no graspkit is on PATH")
    return exe


def run_cli(exe, *args):
    done = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stdout
