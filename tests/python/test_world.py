"""Worlds: building, saving and loading back, clones, and bodies' mass properties."""

import math

import numpy as np
import pytest

import graspkit


def test_mass_properties_equal_graspits(graspit_data, reference):
    checked = 0
    for body in reference["mass_properties"]:
        if not body.get("load_ok"):
            continue
        world = graspkit.World()
        b = world.add_object(graspit_data / body["file"])
        assert b.mass == pytest.approx(body["mass_g"])
        np.testing.assert_allclose(b.cog, body["cog_mm"], atol=1e-4 * max(1, b.max_radius))
        np.testing.assert_allclose(b.inertia.ravel(), body["inertia"],
                                   rtol=1e-4, atol=1e-4 * max(body["inertia"]))
        assert b.max_radius == pytest.approx(body["max_radius_mm"], rel=1e-5)  # GraspIt!: floats
        assert b.material == body["material"]
        assert b.triangle_count == body["triangles"]
        checked += 1
    assert checked >= 10


def test_box_geometry_is_the_files(models):
    # models/objects/box.iv: 60 x 60 x 120 mm centred on its origin.
    world = graspkit.World()
    box = world.add_object(models / "objects/box.xml", graspkit.pose((10, 0, 0)))
    v = box.vertices("body")
    np.testing.assert_allclose(v.min(axis=0), (-30, -30, -60))
    np.testing.assert_allclose(v.max(axis=0), (30, 30, 60))
    np.testing.assert_allclose(box.vertices().min(axis=0), (-20, -30, -60))
    assert box.triangles().shape == (box.triangle_count, 3) == (12, 3)
    assert box.max_radius == pytest.approx(math.sqrt(30**2 + 30**2 + 60**2))
    assert box.mass == 300 and box.kind == "graspable" and box.is_dynamic


def test_saved_world_loads_back_the_same(graspit_data, models, tmp_path):
    world = graspkit.World()
    mug = world.add_object(models / "objects/mug.xml", graspkit.pose((0, 0, 100)))
    world.add_obstacle(models / "obstacles/floor.xml")
    hand = world.add_robot(graspit_data / "models/robots/Barrett/Barrett.xml",
                           graspkit.axis_angle((1, 0, 0), 0.3, (5, -20, 0)))
    hand.set_dofs([0.2, 0.5, 0.6, 0.7])
    file = tmp_path / "saved.xml"
    world.save(file)
    assert world.file == str(file)

    back = graspkit.load_world(file)
    assert [b.name for b in back.bodies] == [b.name for b in world.bodies]
    assert [b.kind for b in back.bodies] == ["graspable", "obstacle"]
    np.testing.assert_allclose(back.body(mug.name).pose, mug.pose, atol=1e-9)
    r = back.robot("Barrett")
    np.testing.assert_allclose(r.pose, hand.pose, atol=1e-9)
    np.testing.assert_allclose(r.dofs, hand.dofs, atol=1e-12)
    for a, b in zip(r.link_poses(), hand.link_poses()):
        np.testing.assert_allclose(a, b, atol=1e-9)


def test_a_clone_is_independent(graspit_data):
    world = graspkit.load_world(graspit_data / "worlds/plannerMug.xml")
    copy = world.clone()
    copy.robot().set_dofs([0, 1, 1, 1])
    copy.body("mug").pose = graspkit.pose((0, 0, 500))
    np.testing.assert_array_equal(world.robot().dofs, [0, 0, 0, 0])
    assert world.body("mug").pose[2, 3] == pytest.approx(105.818, abs=1e-3)
    assert copy.body("mug").pose[2, 3] == 500


def test_set_dofs_limits(graspit_data):
    hand = graspkit.World().add_robot(graspit_data / "models/robots/Barrett/Barrett.xml")
    low, high = hand.dof_limits
    hand.set_dofs(high + 1)
    np.testing.assert_allclose(hand.dofs, high)
    hand.set_dofs(high + 1, limits="ignore")
    np.testing.assert_allclose(hand.dofs, high + 1)
    with pytest.raises(ValueError, match="outside its range"):
        hand.set_dofs(high + 1, limits="error")


def test_collisions(models):
    world = graspkit.World()
    world.add_object(models / "objects/box.xml")
    world.add_obstacle(models / "objects/sphere.xml", graspkit.pose((200, 0, 0)))
    assert not world.collides()
    world.bodies[1].pose = graspkit.pose((30, 0, 0))
    assert world.collides()
