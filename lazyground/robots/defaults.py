"""Robot defaults that live with the robot: ``models/<robot>/robot.yaml``.

A robot folder holds its model (URDF/SDF) and a ``robot.yaml`` that says what
every scene using the robot would otherwise repeat: the base link, the planned
joints, the end effector, named poses (``tucked``), the planner settings that
suit it, acceleration limits for time parameterisation (URDFs carry velocity
limits only) and, for cars, the steering kinematics. A scene's own keys win;
a scene without a ``planner:`` block plans with the robot's.

No pydrake here: loading a scene reads this file.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import yaml

from lazyground.planner_spec import PlannerSpec
from lazyground.typed_yaml import SceneError, checked, load_dataclass, load_yaml, non_negative, positive

DEFAULTS_FILE = "robot.yaml"
AXES = ("x", "y", "z", "-x", "-y", "-z")


@dataclass(frozen=True)
class EndEffectorSpec:
    """The gripper frame and how it grasps: ``approach_axis`` points from the palm towards the
    object, ``closing_axis`` is the direction the fingers close along, ``opening`` the widest
    object (m) the fingers take."""

    frame: str
    offset_xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)  # grasp point in ``frame``
    offset_rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)
    approach_axis: str = "x"
    closing_axis: str = "y"
    opening: float | None = checked(positive, default=None)
    # how far the fingertips reach past the grasp point along the approach axis (m); a grasp's `depth` is how far the
    # fingers reach over the object, so the grasp point sits `depth - fingertip` past the object's face (issue 34)
    fingertip: float = checked(non_negative, default=0.0)

    def validate(self) -> str | None:
        for key in ("approach_axis", "closing_axis"):
            if getattr(self, key) not in AXES:
                return f"{key}: {getattr(self, key)!r} is not one of {', '.join(AXES)}"
        if self.approach_axis.strip("-") == self.closing_axis.strip("-"):
            return "closing_axis: must differ from approach_axis"
        return None


@dataclass(frozen=True)
class CarKinematics:
    """A car-like robot's steering: the minimum turning radius is wheelbase / tan(max_steering_angle)."""

    wheelbase: float = checked(positive)
    max_steering_angle: float = checked(positive)  # rad

    @property
    def min_turning_radius(self) -> float:
        return self.wheelbase / math.tan(self.max_steering_angle)


@dataclass(frozen=True)
class RobotDefaults:
    """The contents of a ``robot.yaml`` (see module docstring); paths are relative to it."""

    model: str
    base_link: str = "base_link"
    planned_joints: tuple[str, ...] | None = None
    end_effector: EndEffectorSpec | None = None
    srdf: str | None = None
    start: str | None = None  # the named pose a scene without ``robot.start`` starts from
    named_poses: dict[str, dict[str, float]] = field(default_factory=dict)
    planner: dict[str, Any] = field(default_factory=dict)  # keys as in a scene's ``planner:`` block
    acceleration_limits: dict[str, float] = field(default_factory=dict)  # per joint, rad/s^2 or m/s^2
    default_acceleration: float | None = checked(positive, default=None)  # joints not listed above
    velocity_limits: dict[str, float] = field(default_factory=dict)  # per joint; overrides the URDF's
    xacro_args: dict[str, str | bool | int | float] = field(default_factory=dict)  # a .xacro model's arguments (a scene's win)
    kinematics: CarKinematics | None = None
    source: str = ""  # the robot.yaml this came from (set by the loader)

    def validate(self) -> str | None:
        if self.start is not None and self.start not in self.named_poses:
            return f"start: no named pose {self.start!r} (named: {', '.join(self.named_poses) or 'none'})"
        problem = _planner_problem(self.planner)
        if problem:
            return problem
        for kind, table in (("acceleration_limits", self.acceleration_limits), ("velocity_limits", self.velocity_limits)):
            for joint, value in table.items():
                if not value > 0:
                    return f"{kind}.{joint}: must be > 0, got {value:g}"
        return None

    @property
    def folder(self) -> Path:
        return Path(self.source).parent

    def path(self, relative: str) -> Path:
        """A file named in this robot.yaml, resolved against its folder."""
        return (self.folder / relative).resolve()

    def acceleration_limit(self, joint: str) -> float | None:
        return self.acceleration_limits.get(joint, self.default_acceleration)


def _planner_problem(planner: dict) -> str | None:
    """The robot's planner block checked as a scene's (the declarations of lazyground.settings), or None."""
    try:
        load_dataclass(planner, PlannerSpec, "planner")
    except SceneError as exc:
        return str(exc)
    return None


def defaults_for_model(model_file: str | Path) -> RobotDefaults | None:
    """The defaults beside a model file (its folder's ``robot.yaml``), or None when there are none.

    Raises:
        SceneError: the robot.yaml exists but is invalid (one line naming it and the key).
    """
    path = Path(model_file).resolve().parent / DEFAULTS_FILE
    return load_robot_defaults(path) if path.is_file() else None


@functools.lru_cache(maxsize=32)
def load_robot_defaults(path: Path) -> RobotDefaults:
    """Read one ``robot.yaml`` strictly (cached by path; the files ship with the package)."""
    try:
        data = load_yaml(Path(path).read_text())
    except (OSError, yaml.YAMLError) as exc:
        raise SceneError(f"{path}: cannot read robot defaults: {str(exc).splitlines()[0]}") from None
    try:
        out = load_dataclass(data if data is not None else {}, RobotDefaults, "")
    except SceneError as exc:
        raise SceneError(f"{path}: {exc}") from None
    return replace(out, source=str(path))
