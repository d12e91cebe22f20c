"""Dynamics, validation, datasets and generated objects from Python, against independent
truths: drop.xml's closed-form resting height, `graspkit simulate`'s own report, a dataset's
round trip through its file, and the Body XML a generated object is saved as."""

import json
import os
import subprocess

import numpy as np
import pytest

import graspkit
from conftest import PROJECT

MODELS = PROJECT / "models"


def drop_world():
    return graspkit.load_world(MODELS / "worlds" / "drop.xml", roots=[MODELS])


def test_a_dropped_box_rests_at_half_its_height():
    world = drop_world()
    report = world.simulate(seconds=1.0, trajectory=True, every=100)
    assert report["completed"] and report["stop_reason"] == "completed"
    assert report["steps"] == 400
    assert len(report["trajectory"]) == 1 + 4
    assert world.body("box").pose[2, 3] == pytest.approx(60.1, abs=0.2)
    # The first frame is the state before any step: the box where the file put it.
    assert report["trajectory"][0]["bodies"][1]["position"][2] == pytest.approx(160.0)


def test_simulate_gives_what_graspkit_simulate_prints():
    exe = os.environ.get("GRASPKIT_EXE")
    if not exe:
        pytest.skip("graspkit: SKIPPED: GRASPKIT_EXE not set")
    cli = json.loads(subprocess.run(
        [exe, "-q", "simulate", MODELS / "worlds" / "drop.xml", "--root", MODELS,
         "--seconds", "0.3", "--json"], capture_output=True, text=True, check=True).stdout)
    world = drop_world()
    report = world.simulate(seconds=0.3)
    assert report["steps"] == cli["steps"]
    assert world.body("box").pose[:3, 3] == pytest.approx(cli["bodies"][1]["position"],
                                                          rel=1e-12, abs=1e-12)


def test_gravity_off_leaves_the_box_in_the_air():
    world = drop_world()
    world.simulate(seconds=0.2, gravity=(0, 0, 0))
    assert world.body("box").pose[2, 3] == pytest.approx(160.0, abs=1e-9)


def test_bad_settings_are_errors_not_crashes():
    world = drop_world()
    with pytest.raises(ValueError, match="every"):
        world.simulate(every=0)
    with pytest.raises(graspkit.Error):
        world.step(dt=1.0)  # longer than the longest step
    with pytest.raises(graspkit.Error, match="hand"):
        graspkit.validate(world)  # no hand holds the box
    with pytest.raises((graspkit.Error, ValueError)):
        world.simulate(gravity=(0, float("nan"), 0))


def test_remove_body_keeps_later_views_on_their_bodies():
    world = graspkit.World()
    views = [world.add_object(MODELS / "objects" / "box.xml") for _ in range(3)]
    names = [v.name for v in views]
    world.remove_body(views[0])
    assert views[2].name == names[2] and views[2].index == 1
    with pytest.raises(IndexError):
        views[0].name
    world.remove_body(names[1])
    assert [b.name for b in world.bodies] == [names[2]]
    with pytest.raises(ValueError):
        world.remove_body("no such body")


def test_a_dataset_round_trips_through_its_file(tmp_path):
    made = graspkit.generate_object(tmp_path, 2, seed=4)
    assert made["file"].endswith(made["name"] + ".xml")
    assert graspkit.World().add_object(made["file"]).mass == pytest.approx(made["mass"])
    data = graspkit.plan_dataset(MODELS / "robots" / "parallel_jaw" / "parallel_jaw.xml",
                                 made["file"], grasps=2, steps=600, seed=3)
    assert len(data) >= 1
    data.save(tmp_path / "d.h5")
    again = graspkit.load_dataset(tmp_path / "d.h5")
    assert again.object_name == data.object_name and again.seed == 3
    for a, b in zip(data.grasps, again.grasps):
        assert a.epsilon == b.epsilon and a.volume == b.volume
        assert np.array_equal(a.pose, b.pose) and np.array_equal(a.closed_dofs, b.closed_dofs)
        assert a.held is None
    with pytest.raises(graspkit.Error):
        graspkit.load_dataset(tmp_path / "missing.h5")
    with pytest.raises(graspkit.Error, match="teapot"):
        graspkit.generate_object(tmp_path, 0, kinds=["teapot"])


def test_load_options_are_checked():
    urdf = MODELS / "robots" / "urdf_gripper" / "urdf_gripper.urdf"
    with pytest.raises(ValueError, match="close"):
        graspkit.load_world(urdf, close={0: "up"})
    with pytest.raises(graspkit.Error, match="unobtainium"):
        graspkit.load_world(urdf, urdf_material="unobtainium")
    closed_up = graspkit.load_world(urdf, close={0: "+"})
    assert closed_up.robot().dofs.shape[0] >= 1
