"""Poses and forward/inverse kinematics: closed forms, GraspIt!'s link poses, the CLI's JSON."""

import json
import math

import numpy as np
import pytest

import graspkit
from conftest import run_cli


def quaternion_matrix(w, x, y, z):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def test_pose_from_translation_and_quaternion_is_the_textbook_matrix():
    q = np.array([0.3, -0.5, 0.7, 0.2])
    q /= np.linalg.norm(q)
    m = graspkit.pose((1, 2, 3), q)
    np.testing.assert_allclose(m[:3, :3], quaternion_matrix(*q), atol=1e-12)
    np.testing.assert_allclose(m[:3, 3], (1, 2, 3))
    np.testing.assert_array_equal(m[3], (0, 0, 0, 1))
    t, back = graspkit.translation_quaternion(m)
    np.testing.assert_allclose(t, (1, 2, 3))
    np.testing.assert_allclose(back, q if q[0] >= 0 else -q, atol=1e-12)
    # The pair form is accepted wherever a pose is read.
    np.testing.assert_allclose(graspkit.translation_quaternion(((1, 2, 3), q))[1], back)


def test_axis_angle_quarter_turn_about_z_takes_x_to_y():
    m = graspkit.axis_angle((0, 0, 2), math.pi / 2, (5, 0, 0))
    np.testing.assert_allclose(m[:3, :3] @ (1, 0, 0), (0, 1, 0), atol=1e-15)
    np.testing.assert_allclose(m[:3, 3], (5, 0, 0))


def tran_matrix(tran):
    m = np.eye(4)
    m[:3, :3] = quaternion_matrix(*tran["q_wxyz"])
    m[:3, 3] = tran["t_mm"]
    return m


@pytest.mark.parametrize("robot", ["models/robots/Barrett/Barrett.xml",
                                   "models/robots/Puma560/Puma560.xml",
                                   "models/robots/HumanHand/HumanHand20DOF.xml"])
def test_link_poses_equal_graspits(graspit_data, reference, robot):
    figures = reference["forward_kinematics"][robot]
    world = graspkit.World()
    r = world.add_robot(graspit_data / robot)
    for name, config in figures["configs"].items():
        r.set_dofs(config.get("requested_dof_values", config["state"]["dof_values"]),
                   limits="ignore")
        np.testing.assert_allclose(r.dofs, config["state"]["dof_values"], atol=1e-9)
        names = r.link_names()
        poses = r.link_poses()
        for c, chain in enumerate(config["state"]["chains"]):
            for l, link in enumerate(chain["links"]):
                assert names[c][l] == link["name"]
                # GraspIt! prints 12 significant digits.
                np.testing.assert_allclose(poses[c][l], tran_matrix(link["tran"]), atol=1e-6,
                                           err_msg=f"{robot} {name} {link['name']}")


def test_link_poses_equal_the_clis_json(graspit_data, graspkit_exe):
    robot = graspit_data / "models/robots/Barrett/Barrett.xml"
    dofs = [0.5, 0.8, 1.0, 1.2]
    cli = json.loads(run_cli(graspkit_exe, "info", robot, "--dofs", ",".join(map(str, dofs)),
                             "--json"))["robots"][0]
    r = graspkit.World().add_robot(robot)
    r.set_dofs(dofs)
    poses = r.link_poses()
    for c, chain in enumerate(cli["chains"]):
        for l, link in enumerate(chain["links"]):
            want = graspkit.pose(link["translation"], link["quaternion"])
            np.testing.assert_allclose(poses[c][l], want, atol=1e-9)


def test_inverse_kinematics_reaches_a_pose_forward_kinematics_gave(graspit_data):
    # A second method: the Puma560's closed form must land where forward kinematics was.
    world = graspkit.World()
    puma = world.add_robot(graspit_data / "models/robots/Puma560/Puma560.xml")
    low, high = puma.dof_limits
    rng = np.random.default_rng(7)
    reached = 0
    for _ in range(10):
        q = low + (high - low) * rng.uniform(0.2, 0.8, size=puma.dof_count)
        puma.set_dofs(q)
        target = puma.link_poses()[0][-1]
        puma.set_dofs(low + 0.5 * (high - low))
        answer = puma.inverse_kinematics(target)
        if not answer:
            continue
        puma.set_dofs(answer.dofs)
        np.testing.assert_allclose(puma.link_poses()[0][-1], target, atol=1e-6)
        reached += 1
    assert reached >= 8


def test_unreachable_pose_is_a_failed_answer_not_an_error(graspit_data):
    puma = graspkit.World().add_robot(graspit_data / "models/robots/Puma560/Puma560.xml")
    answer = puma.inverse_kinematics(graspkit.pose((1e5, 0, 0)))
    assert not answer.success and answer.dofs is None and answer.failure


def test_eigengrasp_amplitudes_round_trip(graspit_data):
    hand = graspkit.World().add_robot(graspit_data / "models/robots/Barrett/Barrett.xml")
    e = hand.eigengrasps()
    assert e["directions"].shape == (len(e["min"]), hand.dof_count)
    a = 0.5 * (e["min"] + e["max"])
    hand.set_eigengrasp_amplitudes(a)
    want = np.clip(e["origin"] + e["norm"] * (a @ e["directions"]), *hand.dof_limits)
    np.testing.assert_allclose(hand.dofs, want, atol=1e-12)
    np.testing.assert_allclose(hand.eigengrasp_amplitudes(), a, atol=1e-9)
