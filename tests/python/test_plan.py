"""Planning: the same grasps as `graspkit plan`, worlds that reload to the same grasp, threads."""

import json
import threading

import numpy as np
import pytest

import graspkit
from conftest import run_cli


@pytest.fixture
def mug_file(graspit_data):
    return graspit_data / "worlds" / "plannerMug.xml"


def test_plan_equals_the_command_line(mug_file, graspkit_exe):
    cli = json.loads(run_cli(graspkit_exe, "plan", mug_file, "--steps", 3000, "--threads", 1,
                             "--top", 5, "--seed", 4, "--json", "-q"))
    world = graspkit.load_world(mug_file)
    grasps = graspkit.plan(world, steps=3000, threads=1, top=5, seed=4)
    assert len(grasps) == len(cli["grasps"]) > 0
    for mine, theirs in zip(grasps, cli["grasps"]):
        assert mine.epsilon == theirs["epsilon"]
        assert mine.volume == theirs["volume"]
        assert mine.contact_count == theirs["contacts"]
        assert mine.force_closure == theirs["force_closure"]
        np.testing.assert_allclose(mine.dofs, theirs["closed_dofs"], atol=1e-12)
        np.testing.assert_allclose(mine.pregrasp_dofs, theirs["open_dofs"], atol=1e-12)
    # The world itself is left as it was.
    np.testing.assert_array_equal(world.robot().dofs, [0, 0, 0, 0])


def test_a_planned_grasps_world_reloads_to_the_same_grasp(mug_file, tmp_path):
    grasps = graspkit.plan(graspkit.load_world(mug_file), steps=3000, threads=1, top=3)
    assert grasps and grasps[0].force_closure
    for i, planned in enumerate(grasps):
        world = planned.world()
        np.testing.assert_allclose(world.robot().dofs, planned.dofs)
        np.testing.assert_allclose(world.robot().pose, planned.pose, atol=1e-12)
        file = tmp_path / f"grasp{i}.xml"
        world.save(file)
        again = graspkit.load_world(file, roots=[mug_file.parents[1]])
        grasp = again.robot().grasp("mug")
        assert grasp.contact_count == planned.contact_count
        assert grasp.epsilon == pytest.approx(planned.epsilon, rel=1e-6, abs=1e-9)
        assert grasp.volume == pytest.approx(planned.volume, rel=1e-6)


def test_grasps_are_best_first(mug_file):
    grasps = graspkit.plan(graspkit.load_world(mug_file), steps=3000, threads=1, top=8)
    keys = [(g.force_closure, g.epsilon) for g in grasps]
    assert keys == sorted(keys, reverse=True)


def test_two_python_threads_plan_side_by_side_with_the_answers_of_one(mug_file):
    # The GIL is released while planning: two threads on two worlds give what each gives alone.
    alone = [graspkit.plan(graspkit.load_world(mug_file), steps=2000, threads=1, seed=s)
             for s in (1, 2)]
    results = [None, None]

    def work(i):
        results[i] = graspkit.plan(graspkit.load_world(mug_file), steps=2000, threads=1,
                                   seed=i + 1)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for got, want in zip(results, alone):
        assert [(g.epsilon, g.volume) for g in got] == [(g.epsilon, g.volume) for g in want]


def test_a_time_budget_plans(mug_file):
    grasps = graspkit.plan(graspkit.load_world(mug_file), seconds=0.3, threads=1)
    assert grasps


def test_planner_and_energy_names(mug_file):
    assert "simann" in graspkit.planners()
    assert "contact" in graspkit.energies()
    world = graspkit.load_world(mug_file)
    with pytest.raises(graspkit.Error, match="no-such-energy"):
        graspkit.plan(world, energy="no-such-energy", steps=10)
    with pytest.raises(graspkit.Error, match="no-such-planner"):
        graspkit.plan(world, planner="no-such-planner", steps=10)
    with pytest.raises(ValueError, match="steps or seconds"):
        graspkit.plan(world, steps=10, seconds=1)
    with pytest.raises(ValueError, match="steps 0 is not valid"):
        graspkit.plan(world, steps=0)
    with pytest.raises(ValueError, match="no body named"):
        graspkit.plan(world, object="teapot", steps=10)
