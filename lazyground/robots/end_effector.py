"""The end effector made explicit: which frame grasps, and along which of its axes.

Grasp regions (grounding/regions.py) are written for a gripper-neutral frame N:

    N.x  the approach axis, from the palm towards the object
    N.y  the closing axis, the direction the fingers close along
    N.z  = N.x x N.y

at the grasp point (midway between the fingers). A robot's tool frame T differs:
the Fetch's ``gripper_link`` is N itself (x forward, fingers along y), a ROS-style
tool frame (``tool0``, ``panda_hand_tcp``) points z forward. ``EndEffectorSpec``
(lazyground/robots/defaults.py) names T, the grasp point in T (``offset_*``) and
T's approach and closing axes; ``X_NT`` maps a region's pose of N to the pose of T
the goal sampler must reach. No pydrake here.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lazyground.geometry import Pose
from lazyground.robots.defaults import EndEffectorSpec, defaults_for_model

LEGACY_FRAME = "gripper_link"  # the frame scenes used before end effectors were explicit

_UNIT = {"x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0)}


def axis_vector(axis: str) -> np.ndarray:
    """The unit vector of ``x|y|z|-x|-y|-z``."""
    sign = -1.0 if axis.startswith("-") else 1.0
    return sign * np.array(_UNIT[axis.lstrip("-")])


def R_GN(spec: EndEffectorSpec) -> np.ndarray:
    """N's axes expressed in the grasp-point frame G (T turned by ``offset_rpy``): columns approach, closing, normal."""
    a, c = axis_vector(spec.approach_axis), axis_vector(spec.closing_axis)
    return np.column_stack([a, c, np.cross(a, c)])


def X_NT(spec: EndEffectorSpec) -> Pose:
    """The tool frame T in the neutral grasp frame N: X_NT = X_NG · X_GT, X_TG = offset."""
    X_NG = np.eye(4)
    X_NG[:3, :3] = R_GN(spec).T
    X_TG = Pose(spec.offset_xyz, spec.offset_rpy).matrix()
    return Pose.from_matrix(X_NG @ np.linalg.inv(X_TG))


def vector_in_tool(spec: EndEffectorSpec, v_N) -> tuple[float, float, float]:
    """A vector given in N (e.g. an approach offset) expressed in T's axes."""
    R_TN = Pose((0.0, 0.0, 0.0), spec.offset_rpy).rotation() @ R_GN(spec)
    return tuple(float(x) for x in R_TN @ np.asarray(v_N, float))


def is_neutral(spec: EndEffectorSpec) -> bool:
    """Whether T is N itself (the Fetch's gripper_link): regions need no mapping."""
    return (spec.approach_axis, spec.closing_axis) == ("x", "y") and not any(spec.offset_xyz) and not any(spec.offset_rpy)


def end_effector_of(robot) -> EndEffectorSpec:
    """The end effector of a scene's robot (a ``RobotSpec``).

    ``robot.end_effector`` may be an ``EndEffectorSpec`` (the scene's mapping form), a frame
    name (the old string form) or None. A frame name that is the robot.yaml's end-effector
    frame takes that file's axes and opening; another name keeps the old convention (x
    approach, y closing); None takes the robot.yaml's, else ``gripper_link``.

    Args:
        robot: the scene's ``RobotSpec`` (its ``model`` a resolved path).
    Returns:
        The spec the grasp regions are mapped through.
    Raises:
        SceneError: the robot.yaml beside the model is invalid.
    """
    given = robot.end_effector
    if isinstance(given, EndEffectorSpec):
        return given
    defaults = defaults_for_model(Path(robot.model)) if robot.model else None
    spec = defaults.end_effector if defaults is not None else None
    if given is None:
        return spec if spec is not None else EndEffectorSpec(frame=LEGACY_FRAME)
    if spec is not None and spec.frame == given:
        return spec
    return EndEffectorSpec(frame=given)


def frame_of(robot) -> str:
    """The end-effector frame name of a scene's robot (see :func:`end_effector_of`)."""
    return end_effector_of(robot).frame
