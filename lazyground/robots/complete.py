"""A scene's robot block completed from what the robot brings: robot.yaml and its SRDF.

``complete_robot(robot, scene_dir, source)`` returns the ``RobotSpec`` every later stage
sees, with:

* ``base_link``, ``planned_joints``, ``end_effector`` and ``srdf`` taken from the robot's
  ``robot.yaml`` where the scene leaves them out;
* ``packages`` folders and ``srdf`` resolved against the scene file's folder;
* ``start`` a plain ``{joint: value}`` mapping: the scene may give a named pose
  (``start: tucked``), a mapping that starts from one and overrides joints
  (``start: {from: default, finger_joint: 0.04}``), or nothing (the robot.yaml's start).
  Named poses are the robot.yaml's ``named_poses`` and the SRDF's ``group_state``s.

No pydrake. Errors are ``SceneError`` lines naming the key.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from lazyground.robots.defaults import RobotDefaults, defaults_for_model
from lazyground.robots.srdf import read_srdf
from lazyground.typed_yaml import SceneError, describe

FROM = "from"  # the key of a start mapping that names the pose it starts from


def named_poses(robot, defaults: RobotDefaults | None) -> dict[str, dict[str, float]]:
    """Named poses: the robot.yaml's, then the SRDF's group states (the SRDF wins on a name clash)."""
    poses = dict(defaults.named_poses) if defaults is not None else {}
    if robot.srdf:
        poses.update(read_srdf(robot.srdf).named_poses)
    return poses


def complete_robot(robot, scene_dir: Path | None, source: str):
    """The robot block with the robot's own defaults filled in (see module docstring).

    Args:
        robot: the scene's ``RobotSpec``, its ``model`` already a resolved path.
        scene_dir: the scene file's folder (relative ``packages`` and ``srdf`` resolve there).
        source: the scene file, for error lines.
    Returns:
        A new ``RobotSpec`` whose ``start`` is a mapping of joint values.
    Raises:
        SceneError: an unknown named pose, a start mapping with non-numbers, a missing SRDF.
    """
    defaults = defaults_for_model(robot.model)
    here = scene_dir if scene_dir is not None else Path.cwd()
    packages = {name: str((here / Path(folder).expanduser()).resolve()) for name, folder in robot.packages.items()}
    srdf = str((here / robot.srdf).resolve()) if robot.srdf else (str(defaults.path(defaults.srdf)) if defaults and defaults.srdf else None)
    if srdf is not None and not Path(srdf).is_file():
        raise SceneError(f"{source}: robot.srdf: file {srdf} not found")
    robot = replace(
        robot,
        packages=packages,
        srdf=srdf,
        base_link=robot.base_link or (defaults.base_link if defaults else "base_link"),
        planned_joints=robot.planned_joints if robot.planned_joints is not None else (defaults.planned_joints if defaults else None),
        end_effector=_end_effector(robot, defaults),
        xacro_args={**(defaults.xacro_args if defaults else {}), **robot.xacro_args},
    )
    try:
        poses = named_poses(robot, defaults)
    except SceneError as exc:
        raise SceneError(f"{source}: robot.srdf: {exc}") from None
    return replace(robot, start=_start(robot.start, poses, defaults, source))


def _end_effector(robot, defaults: RobotDefaults | None):
    """The scene's end effector, else the last mounted tool's robot.yaml's, else the robot's."""
    if robot.end_effector is not None:
        return robot.end_effector
    for tool in reversed(robot.tools):
        tool_defaults = defaults_for_model(tool.model)
        if tool_defaults is not None and tool_defaults.end_effector is not None:
            return tool_defaults.end_effector
    return defaults.end_effector if defaults else None


def _start(start, poses: dict[str, dict[str, float]], defaults: RobotDefaults | None, source: str) -> dict[str, float]:
    if start is None:
        if defaults is None or defaults.start is None:
            raise SceneError(f"{source}: robot.start: required (the robot's folder has no robot.yaml with a start pose)")
        start = defaults.start
    if isinstance(start, str):
        start = {FROM: start}
    base: dict[str, float] = {}
    if FROM in start:
        name = start[FROM]
        if not isinstance(name, str) or name not in poses:
            known = ", ".join(sorted(poses)) or "none"
            raise SceneError(f"{source}: robot.start: no named pose {name!r} (named: {known})")
        base = dict(poses[name])
    for joint, value in start.items():
        if joint == FROM:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise SceneError(f"{source}: robot.start.{joint}: expected a number, got {describe(value)}")
        base[joint] = float(value)
    return base
