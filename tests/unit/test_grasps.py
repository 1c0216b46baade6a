"""Grasp sets and the end-effector mapping (grounding/grasps.py, lazyground/robots/end_effector.py).

No pydrake: the mapping is checked on the region poses themselves. The planning side (a z-forward
tool frame reaching a top grasp pointing down) is tests/drake/test_end_effector_plans.py.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from grounding import GroundingError, ground
from lazyground.geometry import Pose
from lazyground.robots.defaults import EndEffectorSpec
from lazyground.robots.end_effector import X_NT, axis_vector, end_effector_of, vector_in_tool
from lazyground.scene import parse_scene


def _scene(robot: str, objects: str):
    text = textwrap.dedent(robot) + "objects:\n" + textwrap.dedent(objects)
    return parse_scene(text, "<test>")


FETCH = """\
    name: t
    robot: {model: fetch, base: {xyz: [0, 0, 0]}, end_effector: gripper_link, start: {torso_lift_joint: 0.05}}
"""
UR5E = """\
    name: t
    robot: {model: ur5e, base: {xyz: [0, 0, 0]}, start: {elbow_joint: 1.5}}
"""
OBJECTS = """\
    - {id: can1, type: can, geometry: {cylinder: {radius: 0.033, length: 0.12}}, pose: {xyz: [0.5, 0, 0.06]}}
    - {id: wide_can, type: can, geometry: {cylinder: {radius: 0.06, length: 0.12}}, pose: {xyz: [0.5, 0.4, 0.06]}}
    - {id: slab, type: box, geometry: {box: [0.3, 0.06, 0.1]}, pose: {xyz: [0.5, -0.4, 0.05]}}
    - {id: crate, type: box, geometry: {box: [0.3, 0.3, 0.1]}, pose: {xyz: [0.5, -0.8, 0.05]}}
"""


def _tool_axes(region, v):
    """The tool frame's rotation in world for a sample ``v`` of a workspace region."""
    return region.pose_in_world(v).rotation()


def test_cylinder_gets_top_and_side_grasps_all_around():
    (i,) = ground("pick up can1", _scene(FETCH, OBJECTS)).interpretations
    assert [r.label for r in i.goal_regions] == ["top", "side 35%", "side 65%", "angled"]
    rng = np.random.default_rng(0)
    top, low, high, _ = i.goal_regions
    for _ in range(20):
        R = _tool_axes(top, top.sample(rng))
        np.testing.assert_allclose(R[:, 0], [0, 0, -1], atol=1e-9)  # Fetch: x approaches, straight down
        for side in (low, high):
            R = _tool_axes(side, side.sample(rng))
            assert abs(R[2, 0]) < 1e-9 and abs(R[2, 1]) < 1e-9  # approach and closing horizontal
    # the two heights are bands of the can's length, low below high
    assert low.upper[2] <= high.lower[2] + 1e-9 and low.lower[2] >= -0.06 and high.upper[2] <= 0.06
    yaws = [side.sample(rng)[5] for _ in range(200) for side in (low,)]
    assert min(yaws) < -2.5 and max(yaws) > 2.5  # all around the axis


def test_box_gets_top_grasps_besides_faces_only_where_it_fits():
    g = ground("pick up slab", _scene(FETCH, OBJECTS))
    labels = [r.label for r in g.interpretations[0].goal_regions]
    # 0.06 across y fits the 0.10 opening: the +-x faces and the top closing along y; 0.3 along x does not
    assert labels == ["face +x", "face -x", "top y", "angled y"]


@pytest.mark.parametrize("robot", [FETCH, UR5E])
def test_angled_grasps_slant_from_the_vertical_through_the_top_face_centre(robot):
    """Issue 34: the approach tilts 20-50 degrees from straight down about a horizontal closing axis, its line
    through the top face's centre, the grasp point depth - fingertip past it; a can: any yaw; a box: either side."""
    scene = _scene(robot, OBJECTS)
    ee = end_effector_of(scene.robot)
    approach_col, closing_col = (0, 1) if ee.approach_axis == "x" else (2, 1)
    rng = np.random.default_rng(2)
    for name, top_z in (("can1", 0.12), ("slab", 0.1)):
        (angled,) = [r for r in ground(f"pick up {name}", scene).interpretations[0].goal_regions if r.label.startswith("angled")]
        centre = np.array([0.5, 0.0 if name == "can1" else -0.4, top_z])
        tilts, yaws = [], []
        for _ in range(200):
            X = angled.pose_in_world(angled.sample(rng))
            R = X.rotation()
            a, c = R[:, approach_col], R[:, closing_col]
            assert abs(c[2]) < 1e-9  # the fingers close horizontally
            tilt = math.acos(-a[2])
            tilts.append(tilt)
            yaws.append(math.atan2(a[1], a[0]))
            # the grasp point lies on a line along the approach that enters the top face near its centre
            p = np.asarray(X.xyz) + (ee.offset_xyz[2] if ee.approach_axis == "z" else 0.0) * a
            entry = p - a * (p[2] - top_z) / a[2]
            assert np.linalg.norm(entry[:2] - centre[:2]) < 0.01
            depth = (p - entry) @ a + ee.fingertip  # how far the fingertips reach past the face (the grasp point may be short of it)
            assert 0.01 - 1e-9 <= depth <= 0.03 + 1e-9
        assert max(tilts) <= math.radians(50) + 1e-9 and max(tilts) > math.radians(45)
        if name == "can1":
            assert min(yaws) < -2.5 and max(yaws) > 2.5  # from every side
            assert min(tilts) >= math.radians(20) - 1e-9
        else:  # the slab closes across its 0.06 m y: tilted over its +x and -x ends (upright included)
            assert {round(abs(y), 3) for y in yaws if abs(math.sin(y)) < 1e-6} == {0.0, round(math.pi, 3)}


def test_object_wider_than_the_gripper_is_dropped_with_a_note():
    g = ground("pick up a can", _scene(FETCH, OBJECTS))
    assert [i.id for i in g.interpretations] == ["pick:can1"]
    (note,) = [n for n in g.notes if "cannot be grasped" in n]
    assert "wide_can" in note and "0.12 m across" in note and "opening 0.1 m" in note and "0.01 m clearance" in note
    with pytest.raises(GroundingError, match=r"^wide_can cannot be grasped: it is 0.12 m across"):
        ground("pick up wide_can", _scene(FETCH, OBJECTS))
    assert any("crate cannot be grasped: it is 0.3 m across" in n for n in ground("pick up a box", _scene(FETCH, OBJECTS)).notes)


def test_ros_tool_frame_points_its_z_axis_where_the_grasp_approaches():
    scene = _scene(UR5E, OBJECTS)
    ee = end_effector_of(scene.robot)  # from models/ur5e/robot.yaml
    assert (ee.frame, ee.approach_axis, ee.closing_axis, ee.opening) == ("tool_tcp", "z", "y", 0.085)
    (i,) = ground("pick up can1", scene).interpretations
    assert all(r.frame == "tool_tcp" for r in i.goal_regions)
    top, side, *_ = i.goal_regions
    rng = np.random.default_rng(1)
    for _ in range(20):
        R = _tool_axes(top, top.sample(rng))
        np.testing.assert_allclose(R[:, 2], [0, 0, -1], atol=1e-9)  # z (approach) down: never horizontal over the can
        R = _tool_axes(side, side.sample(rng))
        assert abs(R[2, 2]) < 1e-9 and abs(R[2, 1]) < 1e-9
    # the approach offset moves back along the tool's own z
    np.testing.assert_allclose(top.approach, [0, 0, -0.08], atol=1e-12)


def test_same_grasp_point_for_every_frame_convention():
    """Regions for a neutral frame and for a z-forward frame put the grasp point at the same place."""
    fetch_regions = ground("pick up can1", _scene(FETCH, OBJECTS)).interpretations[0].goal_regions
    ur_regions = ground("pick up can1", _scene(UR5E, OBJECTS)).interpretations[0].goal_regions
    v = np.array([-0.01, 0, 0, 0.3, 0, 0])
    X_fetch, X_ur = fetch_regions[0].pose_in_world(v), ur_regions[0].pose_in_world(v)
    np.testing.assert_allclose(X_fetch.xyz, X_ur.xyz, atol=1e-12)
    np.testing.assert_allclose(X_fetch.rotation()[:, 0], X_ur.rotation()[:, 2], atol=1e-12)  # approach
    np.testing.assert_allclose(X_fetch.rotation()[:, 1], X_ur.rotation()[:, 1], atol=1e-12)  # closing


@pytest.mark.parametrize("approach,closing", [("z", "y"), ("-x", "z"), ("y", "-x"), ("x", "y")])
def test_mapping_sends_neutral_axes_to_the_named_tool_axes(approach, closing):
    spec = EndEffectorSpec(frame="t", approach_axis=approach, closing_axis=closing, offset_xyz=(0, 0, 0.1))
    R_NT = X_NT(spec).rotation()
    # T's approach axis, expressed in N, is N.x; its closing axis is N.y
    np.testing.assert_allclose(R_NT @ axis_vector(approach), [1, 0, 0], atol=1e-12)
    np.testing.assert_allclose(R_NT @ axis_vector(closing), [0, 1, 0], atol=1e-12)
    # the grasp point (offset in T) sits at N's origin
    p_N = X_NT(spec).transform_points(np.array([0, 0, 0.1]))[0]
    np.testing.assert_allclose(p_N, 0, atol=1e-12)
    np.testing.assert_allclose(vector_in_tool(spec, (-1, 0, 0)), -axis_vector(approach), atol=1e-12)


def test_old_string_end_effector_keeps_the_x_forward_convention():
    robot = _scene(FETCH, OBJECTS).robot
    assert end_effector_of(robot) == EndEffectorSpec(frame="gripper_link", approach_axis="x", closing_axis="y", opening=0.10, fingertip=0.03)
    other = _scene(FETCH.replace("end_effector: gripper_link", "end_effector: wrist_roll_link"), OBJECTS).robot
    assert end_effector_of(other) == EndEffectorSpec(frame="wrist_roll_link")
    assert Pose().compose(X_NT(end_effector_of(other))) == Pose()
    assert math.isclose(end_effector_of(robot).opening, 0.10)
