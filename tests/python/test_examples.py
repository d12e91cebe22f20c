"""examples/python: each runs as docs/python.md shows it, and what it writes loads back."""

import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import graspkit
from conftest import PROJECT, run_cli

EXAMPLES = PROJECT / "examples" / "python"


def run_example(name, *args, cwd=PROJECT):
    done = subprocess.run([sys.executable, str(EXAMPLES / name), *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=600, env=os.environ)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_plan_default_prints_what_graspkit_plan_finds(graspkit_exe):
    printed = run_example("plan_default.py", "--top", 4, "--steps", 4000)
    cli = json.loads(run_cli(graspkit_exe, "plan", PROJECT / "models/worlds/default.xml",
                             "--top", 4, "--steps", 4000, "--json", "-q"))
    rows = [line.split() for line in printed.splitlines()[2:]]
    assert len(rows) == len(cli["grasps"]) == 4
    for row, grasp in zip(rows, cli["grasps"]):
        assert float(row[1]) == pytest.approx(grasp["epsilon"], abs=1e-5)
        assert float(row[2]) == pytest.approx(grasp["volume"], abs=1e-6)
        assert int(row[3]) == grasp["contacts"]


def test_grasp_dataset_reloads_to_the_same_grasps(graspit_data, tmp_path):
    out = tmp_path / "dataset.npz"
    run_example("grasp_dataset.py", graspit_data, "--out", out, "--steps", 2000, "--objects", 3,
                "--top", 3)
    data = np.load(out)
    assert len(data["objects"]) == 3 and len(data["epsilon"]) > 0
    # Every stored grasp, rebuilt from the file alone (object at the origin, the hand closed from
    # the stored pre-grasp), ends at the stored pose and DOFs with the stored contacts, epsilon
    # and volume.
    for i in range(len(data["epsilon"])):
        world = graspkit.World()
        target = world.add_object(data["objects"][data["object"][i]])
        hand = world.add_robot(str(data["hand"]), data["pregrasp_pose"][i])
        hand.set_dofs(data["pregrasp_dofs"][i], limits="ignore")
        hand.autograsp()
        np.testing.assert_allclose(hand.dofs, data["dofs"][i], atol=1e-12)
        np.testing.assert_allclose(hand.pose, data["pose"][i], atol=1e-9)
        grasp = hand.grasp(target)
        n = data["contact_count"][i]
        assert grasp.contact_count == n
        assert grasp.epsilon == pytest.approx(data["epsilon"][i], rel=1e-6, abs=1e-9)
        assert grasp.volume == pytest.approx(data["volume"][i], rel=1e-6, abs=1e-12)
        stored = data["points"][i][:n]
        for p in grasp.contacts.points:
            assert np.min(np.linalg.norm(stored - p, axis=1)) < 1e-6
