"""Robot defaults beside the model: models/<robot>/robot.yaml."""

from pathlib import Path

import pytest

from lazyground.robots.defaults import defaults_for_model, load_robot_defaults
from lazyground.typed_yaml import SceneError

MODELS = Path(__file__).resolve().parents[2] / "models"


def test_fetch_defaults_name_the_tucked_start_and_the_gripper():
    d = defaults_for_model(MODELS / "fetch" / "fetch.urdf")
    assert d.start == "tucked" and d.named_poses["tucked"]["elbow_flex_joint"] == 1.72
    assert d.end_effector.frame == "gripper_link" and d.end_effector.opening == pytest.approx(0.10)
    assert d.planner["algorithm"] == "bidirectional"
    assert d.acceleration_limit("torso_lift_joint") == 0.5 and d.acceleration_limit("elbow_flex_joint") == 1.5
    assert d.path(d.model) == (MODELS / "fetch" / "fetch.urdf").resolve()


def test_car_turning_radius_from_wheelbase_and_steering():
    k = defaults_for_model(MODELS / "car" / "car.urdf").kinematics
    assert k.min_turning_radius == pytest.approx(2.7 / 0.7002, rel=1e-3)


def test_no_defaults_file_is_none(tmp_path):
    (tmp_path / "arm.urdf").write_text("<robot name='a'/>")
    assert defaults_for_model(tmp_path / "arm.urdf") is None


@pytest.mark.parametrize("text, words", [
    ("model: a.urdf\nstart: home\n", "no named pose 'home'"),
    ("model: a.urdf\nend_effector: {frame: tool0, approach_axis: w}\n", "approach_axis"),
    ("model: a.urdf\nacceleration_limits: {j1: -1}\n", "must be > 0"),
    ("model: a.urdf\nspeed: 3\n", "speed"),
    ("model: a.urdf\nplanner: {algorithm: rrtstar}\n", "planner.algorithm: unknown algorithm 'rrtstar'"),  # #15: settings' checks
    ("model: a.urdf\nplanner: {step_size: -1}\n", "planner.step_size"),
    ("model: a.urdf\nplanner: {per_algorithm: {rrt: {speed: 1}}}\n", "speed"),
])
def test_bad_defaults_are_one_line_naming_the_file(tmp_path, text, words):
    path = tmp_path / "robot.yaml"
    path.write_text(text)
    with pytest.raises(SceneError) as err:
        load_robot_defaults(path)
    message = str(err.value)
    assert "\n" not in message and str(path) in message and words in message


@pytest.mark.parametrize("robot,frame,opening", [("panda", "panda_hand_tcp", 0.08), ("ur5e", "tool_tcp", 0.085)])
def test_arm_defaults_give_a_z_forward_tool_and_named_poses_over_the_planned_joints(robot, frame, opening):
    d = defaults_for_model(MODELS / robot / f"{robot}.urdf")
    ee = d.end_effector
    assert (ee.frame, ee.approach_axis, ee.closing_axis, ee.opening) == (frame, "z", "y", opening)
    assert d.start in d.named_poses and d.path(d.model).is_file()
    for name, pose in d.named_poses.items():
        assert set(pose) == set(d.planned_joints), name
    assert all(d.acceleration_limit(j) > 0 for j in d.planned_joints)
    assert d.planner["algorithm"] == "bidirectional"
