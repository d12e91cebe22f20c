"""Grasp analysis against GraspIt!'s own figures for plannerMug (reference/graspit-figures.json)."""

import numpy as np
import pytest

import graspkit


@pytest.fixture
def mug_world(graspit_data):
    return graspkit.load_world(graspit_data / "worlds" / "plannerMug.xml")


def test_autograsp_closes_to_graspits_dofs_and_contacts(mug_world, reference):
    expected = reference["grasps"]["plannerMug_as_loaded"]["autograsp"]
    hand = mug_world.robot()
    assert hand.name == "Barrett"
    motion = hand.autograsp()
    assert motion.ended == "settled"
    np.testing.assert_allclose(hand.dofs, expected["final_dofs"], atol=1e-3)
    np.testing.assert_array_equal(motion.dofs, hand.dofs)

    grasp = hand.grasp("mug")
    assert grasp.contact_count == expected["num_contacts"] == 6
    assert grasp.epsilon == expected["epsilon_L1"] == -1
    assert not grasp.force_closure
    assert grasp.volume == pytest.approx(expected["volume_L1"], rel=0.01)
    assert grasp.failure is None

    # Each of GraspIt!'s contacts is one of ours: same point, link, normal and friction.
    contacts = grasp.contacts
    assert len(contacts) == 6
    assert contacts.points.shape == (6, 3) and contacts.normals.shape == (6, 3)
    for want in expected["contacts"]:
        distance = np.linalg.norm(contacts.points - np.array(want["pos_world_mm"]), axis=1)
        i = int(np.argmin(distance))
        assert distance[i] < 1e-6
        assert contacts.links[i] == want["body1_link"]
        assert contacts.bodies[i] == want["body2_object"]
        np.testing.assert_allclose(contacts.object_points[i], want["mate_pos_world_mm"], atol=1e-6)
        np.testing.assert_allclose(contacts.normals[i], want["normal_world"], atol=1e-6)
        assert contacts.mu[i] == pytest.approx(want["cof_static"])
    # The contact frames are rotations whose z is the normal.
    for frame, normal in zip(contacts.frames, contacts.normals):
        np.testing.assert_allclose(frame.T @ frame, np.eye(3), atol=1e-9)
        np.testing.assert_allclose(frame[:, 2], normal, atol=1e-12)


def test_named_measures_equal_the_grasps_own(mug_world):
    hand = mug_world.robot()
    hand.autograsp()
    grasp = hand.grasp(mug_world.body("mug"))
    assert set(graspkit.quality_measures()) >= {"epsilon", "volume"}
    assert grasp.quality("epsilon") == grasp.epsilon
    assert grasp.quality("volume") == grasp.volume


def test_linf_space_of_too_many_points_is_refused_by_name(mug_world):
    # 6 contacts of 8 edges: 9^6 Minkowski-sum points, above the engine's limit.
    hand = mug_world.robot()
    hand.autograsp()
    with pytest.raises(graspkit.Error, match="L-infinity wrench space of 6 contacts"):
        hand.grasp("mug", gws="Linf")
    with pytest.raises(ValueError, match="L1"):
        hand.grasp("mug", gws="L2")


def test_an_open_hand_has_no_contacts_and_says_why(mug_world):
    grasp = mug_world.robot().grasp()
    assert grasp.contact_count == 0
    assert grasp.contacts.points.shape == (0, 3)
    assert grasp.epsilon == -1 and grasp.volume == 0
    assert grasp.failure
