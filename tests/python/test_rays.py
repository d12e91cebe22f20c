"""Batched rays and nearest points, NumPy in and out, against the box's closed form."""

import numpy as np
import pytest

import graspkit


@pytest.fixture
def box_scene(models):
    # 60 x 60 x 120 mm box centred at (100, 0, 0).
    world = graspkit.World()
    world.add_object(models / "objects/box.xml", graspkit.pose((100, 0, 0)))
    return world, graspkit.RayScene(world)


def test_rays_hit_the_box_faces_where_geometry_says(box_scene):
    _, scene = box_scene
    rng = np.random.default_rng(3)
    n = 1000
    yz = rng.uniform(-25, 25, size=(n, 2)) * (1, 2)  # inside the -x face
    origins = np.column_stack([np.zeros(n), yz])
    directions = np.tile((2.0, 0, 0), (n, 1))  # any length
    hits = scene.intersect(origins, directions)
    assert len(hits) == n and hits.hit.all()
    np.testing.assert_allclose(hits.distance, 70.0, atol=1e-4)
    np.testing.assert_allclose(hits.point, np.column_stack([np.full(n, 70.0), yz]), atol=1e-4)
    np.testing.assert_allclose(np.abs(hits.normal[:, 0]), 1.0, atol=1e-6)
    assert (hits.body == 0).all() and scene.body_names == ["box"]
    assert ((hits.triangle >= 0) & (hits.triangle < 12)).all()


def test_misses_and_max_distance(box_scene):
    _, scene = box_scene
    origins = np.array([[0.0, 0, 0], [0, 100, 0], [0, 0, 0]])
    directions = np.array([[1.0, 0, 0], [1, 0, 0], [-1, 0, 0]])
    hits = scene.intersect(origins, directions, max_distance=80)
    np.testing.assert_array_equal(hits.hit, [True, False, False])
    np.testing.assert_array_equal(hits.body, [0, -1, -1])
    assert np.isinf(hits.distance[1:]).all() and np.isnan(hits.point[1:]).all()
    assert not scene.intersect(origins[:1], directions[:1], max_distance=60).hit[0]


def test_nearest_points_are_the_projections_on_the_faces(box_scene):
    _, scene = box_scene
    points = np.array([[100.0, 0, 80], [100, 50, 0], [0, 0, 0], [95, 1, 2]])
    near = scene.nearest(points)
    np.testing.assert_allclose(near.point[0], (100, 0, 60), atol=1e-6)
    np.testing.assert_allclose(near.distance, (20, 20, 70, 25), atol=1e-6)
    # From inside: the -x face (25 mm) is nearer than +-y (29, 31), +x (35) or +-z (58, 62).
    np.testing.assert_allclose(near.point[3], (70, 1, 2), atol=1e-6)
    far = scene.nearest(points, max_distance=21)
    np.testing.assert_array_equal(far.hit, [True, True, False, False])


def test_update_follows_the_world(box_scene):
    world, scene = box_scene
    world.bodies[0].pose = graspkit.pose((200, 0, 0))
    stale = scene.intersect([[0, 0, 0]], [[1, 0, 0]])
    assert stale.distance[0] == pytest.approx(70)
    scene.update(world)
    assert scene.intersect([[0, 0, 0]], [[1, 0, 0]]).distance[0] == pytest.approx(170)


def test_bad_batches_raise_before_tracing(box_scene):
    world, scene = box_scene
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        scene.intersect(np.zeros((4, 2)), np.zeros((4, 2)))
    with pytest.raises(ValueError, match="2 origins but 1 directions"):
        scene.intersect(np.zeros((2, 3)), [[1, 0, 0]])
    with pytest.raises(ValueError, match="ray 1: the direction is zero"):
        scene.intersect(np.zeros((2, 3)), [[1, 0, 0], [0, 0, 0]])
    with pytest.raises(ValueError, match="ray 0: a value is not a finite number"):
        scene.intersect([[np.nan, 0, 0]], [[1, 0, 0]])
    with pytest.raises(ValueError, match="point 0"):
        scene.nearest([[np.inf, 0, 0]])
    with pytest.raises(ValueError, match="max_distance"):
        scene.intersect([[0, 0, 0]], [[1, 0, 0]], max_distance=-1)
    with pytest.raises(ValueError, match="another world"):
        scene.update(graspkit.World())


def test_queries_in_threads_while_the_scene_updates(models):
    # Queries release the GIL; update() waits for them, so every answer is one of the two poses.
    import threading
    world = graspkit.World()
    box = world.add_object(models / "objects/box.xml", graspkit.pose((100, 0, 0)))
    scene = graspkit.RayScene(world)
    origins = np.zeros((20000, 3))
    directions = np.tile((1.0, 0, 0), (20000, 1))
    seen = set()
    stop = threading.Event()

    def query():
        while not stop.is_set():
            seen.update(np.unique(np.round(scene.intersect(origins, directions).distance, 6)))

    workers = [threading.Thread(target=query) for _ in range(2)]
    for w in workers:
        w.start()
    for i in range(50):
        box.pose = graspkit.pose((100 + 100 * (i % 2), 0, 0))
        scene.update(world)
    stop.set()
    for w in workers:
        w.join()
    assert seen <= {70.0, 170.0} and seen
