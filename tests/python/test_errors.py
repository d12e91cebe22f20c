"""Every error path raises a Python exception; the engine's carry file, line and element."""

import math
import os
import warnings

import numpy as np
import pytest

import graspkit

BAD_ROBOT = """<?xml version="1.0"?>
<robot type="Hand">
  <palm>palm.xml</palm>
  <dof type="r">
    <defaultVelocity>1.0</defaultVelocity>
    <maxEffort>2.5e+9</maxEffort>
    <Kp>1e+11</Kp>
    <Kd>1e+7</Kd>
    <draggerScale>20</draggerScale>
  </dof>
  <chain>
    <transform><translation>0 0 0</translation></transform>
    <joint type="Revolute">
      <theta>d7</theta><d>0</d><a>10</a><alpha>0</alpha>
      <minValue>0</minValue><maxValue>90</maxValue>
    </joint>
    <link dynamicJointType="Revolute">link.xml</link>
  </chain>
</robot>
"""


def test_a_missing_file_names_it(tmp_path):
    missing = tmp_path / "nowhere.xml"
    with pytest.raises(graspkit.Error) as caught:
        graspkit.load_world(missing)
    assert caught.value.file == str(missing)
    assert str(missing) in str(caught.value)


def test_malformed_xml_names_file_and_line(tmp_path):
    file = tmp_path / "broken.xml"
    file.write_text("<?xml version='1.0'?>\n<world>\n  <graspableBody>\n</world>\n")
    with pytest.raises(graspkit.Error) as caught:
        graspkit.load_world(file)
    e = caught.value
    assert e.file == str(file) and e.line > 0 and e.message
    assert str(e).startswith(f"{file}:{e.line}:")


def test_a_robot_file_error_names_the_element(tmp_path, models):
    # GraspIt!'s layout: a robot's link files in iv/ beside it.
    (tmp_path / "iv").mkdir()
    for name in ("palm.xml", "link.xml"):
        (tmp_path / "iv" / name).write_text((models / "objects/box.xml").read_text())
    (tmp_path / "iv/box.iv").write_text((models / "objects/box.iv").read_text())
    robot = tmp_path / "bad.xml"
    robot.write_text(BAD_ROBOT)
    with pytest.raises(graspkit.Error) as caught:
        graspkit.World().add_robot(robot)
    e = caught.value
    assert e.file == str(robot) and e.line == 14 and "theta" in e.element + e.message
    assert "d7" in e.message


def test_bad_values_raise_value_errors(graspit_data):
    world = graspkit.load_world(graspit_data / "worlds/plannerMug.xml")
    hand = world.robot()
    with pytest.raises(ValueError, match="4 values expected"):
        hand.set_dofs([0, 0])
    with pytest.raises(ValueError, match="not finite"):
        hand.set_dofs([0, math.nan, 0, 0])
    with pytest.raises(ValueError, match="not a rotation"):
        hand.pose = np.diag([2.0, 1, 1, 1])
    with pytest.raises(ValueError, match="4x4"):
        hand.pose = np.eye(3)
    with pytest.raises(ValueError, match="finite"):
        world.body("mug").pose = np.full((4, 4), np.nan)
    with pytest.raises(ValueError, match="quaternion is zero"):
        graspkit.pose((0, 0, 0), (0, 0, 0, 0))
    # Huge components name their rotation (a quarter turn about x), not the identity.
    turned = graspkit.pose((0, 0, 0), (1e300, 1e300, 0, 0))
    assert abs(turned[1][2] + 1.0) < 1e-12 and abs(turned[2][1] - 1.0) < 1e-12
    with pytest.raises(ValueError, match="frame"):
        world.body("mug").vertices("camera")
    with pytest.raises(ValueError, match="limits"):
        hand.set_dofs([0, 0, 0, 0], limits="loose")
    with pytest.raises(ValueError, match="max_steps"):
        hand.autograsp(max_steps=0)
    with pytest.raises(ValueError, match="step"):
        hand.approach_to_contact(step=0)
    with pytest.raises(ValueError, match="amplitudes"):
        hand.set_eigengrasp_amplitudes([1, 2, 3, 4, 5, 6, 7])


def test_lookups_raise(graspit_data):
    barrett = graspit_data / "models/robots/Barrett/Barrett.xml"
    world = graspkit.load_world(graspit_data / "worlds/plannerMug.xml")
    with pytest.raises(IndexError, match="robot 3 out of range"):
        world.robot(3)
    with pytest.raises(ValueError, match="no robot named 'Shadow'"):
        world.robot("Shadow")
    with pytest.raises(KeyError, match="teapot"):
        world.body("teapot")
    with pytest.raises(ValueError, match="no body named 'teapot'"):
        world.robot().grasp("teapot")
    with pytest.raises(ValueError, match="another world"):
        world.robot().grasp(world.clone().body("mug"))
    with pytest.raises(TypeError):
        world.robot().grasp(3.5)
    with pytest.raises(IndexError, match="chain 9"):
        world.robot().inverse_kinematics(np.eye(4), chain=9)
    with pytest.raises(graspkit.Error, match="no-such-measure"):
        world.robot().grasp().quality("no-such-measure")
    with pytest.raises(ValueError, match="no hand"):
        graspkit.World().robot()
    with pytest.raises(ValueError, match="no graspable body"):
        hand_alone = graspkit.World()
        hand_alone.add_robot(barrett)
        graspkit.plan(hand_alone, steps=1)


def test_a_broken_plugin_is_an_error_naming_the_file():
    corpus = os.environ.get("GRASPKIT_PLUGIN_CORPUS")
    if not corpus:
        pytest.fail("GRASPKIT_PLUGIN_CORPUS is not set (ctest sets it)")
    for name in ("broken/no_symbol.so", "broken/wrong_abi.so", "broken/not_elf.so"):
        file = os.path.join(corpus, name)
        with pytest.raises(graspkit.Error) as caught:
            graspkit.load_plugin(file)
        assert file in str(caught.value) or caught.value.file == file
    with pytest.raises(graspkit.Error):
        graspkit.load_plugin("/nonexistent/plugin.so")


def test_engine_warnings_are_python_warnings_of_their_kind(tmp_path, models):
    body = tmp_path / "odd.xml"
    body.write_text((models / "objects/box.xml").read_text().replace(
        "<mass>300</mass>", "<mass>300</mass>\n    <colour>red</colour>"))
    (tmp_path / "box.iv").write_text((models / "objects/box.iv").read_text())
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        graspkit.World().add_object(body)
    kinds = [w.category for w in seen]
    assert graspkit.UnknownElementWarning in kinds
    assert issubclass(graspkit.UnknownElementWarning, graspkit.GraspkitWarning)
    assert any("colour" in str(w.message) and str(body) in str(w.message) for w in seen)
    # A filter that makes them errors makes the call raise.
    # ... and leaves the world as it was (no body added behind the exception).
    with warnings.catch_warnings():
        warnings.simplefilter("error", graspkit.GraspkitWarning)
        world = graspkit.World()
        with pytest.raises(graspkit.UnknownElementWarning):
            world.add_object(body)
        assert len(world.bodies) == 0


def test_values_numpy_cannot_convert_raise_instead_of_crashing(graspit_data):
    # A str or an object where a pose, DOFs or points belong: NumPy cannot make numbers of it
    # (this once crashed the interpreter for poses).
    world = graspkit.load_world(graspit_data / "worlds/plannerMug.xml")
    hand = world.robot()
    for bad in ("abc", None, object()):
        with pytest.raises(ValueError, match="4x4"):
            hand.pose = bad
        with pytest.raises(ValueError, match="1-D sequence"):
            hand.set_dofs(bad)
        with pytest.raises(ValueError, match=r"\(N, 3\)"):
            graspkit.RayScene(world).intersect(bad, bad)
        with pytest.raises(ValueError, match=r"\(N, 3\)"):
            graspkit.RayScene(world).nearest(bad)
    with pytest.raises(ValueError, match="translation"):
        graspkit.pose("abc", (1, 0, 0, 0))
    # Past the 1e9 mm every front end takes, as a tuple and as a matrix.
    with pytest.raises(ValueError, match="lies past 1e9 mm"):
        hand.pose = ((1e300, 0, 0), (1, 0, 0, 0))
    far = np.eye(4)
    far[0, 3] = 1e300
    with pytest.raises(ValueError, match="lies past 1e9 mm"):
        hand.pose = far
    with pytest.raises(ValueError, match="not a finite number"):
        hand.inverse_kinematics(np.full((4, 4), np.nan))
    with pytest.raises(graspkit.Error, match="not a regular file"):
        world.add_object("/")
    # A folder is never replaced by a save (docs/security.md, "Files graspkit writes").
    with pytest.raises(graspkit.Error, match="not a regular file \\(a folder\\)"):
        world.save("/tmp")
