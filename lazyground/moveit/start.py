"""Start states (#15): from a MoveIt joint state, a motion-plan request, a named pose of the
robot, or ``name=value`` pairs; checked against the model's joint limits.

One set of options serves ``import-moveit`` and ``plan`` (their flags: :mod:`lazyground.cli_options`). A value within :data:`LIMIT_TOLERANCE` outside a joint
limit (recorded sensor noise such as -1.5e-08 on the torso) is clamped with a warning;
further out is an error naming the joint. No pydrake: limits are read from the URDF.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import yaml

from lazyground.robots.defaults import RobotDefaults
from lazyground.typed_yaml import SceneError, load_yaml

LIMIT_TOLERANCE = 1e-6


@dataclass(frozen=True)
class StartOptions:
    """What the user asked for; every field may be None. ``joints`` applies last."""

    name: str | None = None  # --start NAME
    request: str | None = None  # --start-from REQUEST.yaml
    joints: str | None = None  # --start-joints name=value,...

    @property
    def given(self) -> bool:
        return any(v is not None for v in (self.name, self.request, self.joints))


def parse_joints(text: str) -> dict[str, float]:
    """``'a=0.1,b=-2'`` -> {a: 0.1, b: -2.0}.

    Raises:
        SceneError: a pair without ``=`` or a value that is not a finite number.
    """
    out = {}
    for pair in filter(None, (p.strip() for p in text.split(","))):
        name, sep, value = pair.partition("=")
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        if not sep or not name.strip() or not math.isfinite(number):
            raise SceneError(f"--start-joints: expected name=value pairs separated by commas, got {pair!r}")
        out[name.strip()] = number
    if not out:
        raise SceneError("--start-joints: no name=value pairs given")
    return out


def joint_state_values(state, where: str) -> dict[str, float]:
    """A sensor_msgs/JointState mapping's {name: position}.

    Raises:
        SceneError: names and positions that are not lists of equal length, or non-numbers.
    """
    if not isinstance(state, dict):
        raise SceneError(f"{where}: expected a mapping with name and position")
    names, positions = state.get("name") or [], state.get("position") or []
    if not isinstance(names, list) or not isinstance(positions, list) or len(names) != len(positions):
        raise SceneError(f"{where}: name and position must be lists of equal length")
    out = {}
    for n, p in zip(names, positions):
        if isinstance(p, bool) or not isinstance(p, (int, float)) or not math.isfinite(p):
            raise SceneError(f"{where}.position ({n}): expected a finite number, got {p!r}")
        out[str(n)] = float(p)
    return out


def request_start(path: str | Path) -> dict[str, float]:
    """A MotionPlanRequest file's start_state.joint_state.

    Raises:
        SceneError: unreadable, not a motion-plan request, or no joint state.
    """
    from lazyground.scene.file_kind import FileKind, kind_of_mapping, kind_of_text

    try:
        text = Path(path).read_text(encoding="utf-8")
        data = load_yaml(text)
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise SceneError(f"{path}: cannot read the motion-plan request: {str(exc).splitlines()[0]}") from None
    kind = kind_of_mapping(data) if isinstance(data, dict) else kind_of_text(text)
    if kind is not FileKind.MOTION_PLAN_REQUEST:
        what = "not one" if kind is FileKind.OTHER else kind.value
        raise SceneError(f"{path}: --start-from expects a MoveIt motion-plan request (start_state.joint_state); this is {what}")
    state = (data.get("start_state") or {}).get("joint_state") if isinstance(data.get("start_state"), dict) else None
    if not state:
        raise SceneError(f"{path}: start_state.joint_state is missing")
    return joint_state_values(state, f"{path}: start_state.joint_state")


def resolve_start(base: dict[str, float], base_source: str, options: StartOptions, defaults: RobotDefaults,
                  planned: tuple[str, ...]) -> tuple[dict[str, float], str, list[str]]:
    """The start over ``planned`` joints: ``base`` (the scene's), replaced by --start or
    --start-from, then --start-joints; joints still missing come from the robot's default pose.

    Returns:
        (start, a phrase naming where it came from, warnings).

    Raises:
        SceneError: an unknown named pose, --start with --start-from, or a joint that is not planned.
    """
    warnings: list[str] = []
    if options.name is not None and options.request is not None:
        raise SceneError("--start and --start-from: give one of them")
    values, source = dict(base), base_source
    if options.name is not None:
        if options.name not in defaults.named_poses:
            raise SceneError(f"--start: no named pose {options.name!r} (named: {', '.join(defaults.named_poses) or 'none'})")
        values, source = dict(defaults.named_poses[options.name]), f"named pose {options.name!r}"
    elif options.request is not None:
        values, source = request_start(options.request), f"motion-plan request {Path(options.request).name}"
    if options.joints is not None:
        given = parse_joints(options.joints)
        unknown = [j for j in given if j not in planned]
        if unknown:
            raise SceneError(f"--start-joints: {', '.join(unknown)} is not a planned joint (planned: {', '.join(planned)})")
        values.update(given)
        source += " with --start-joints"
    fallback = defaults.named_poses.get(defaults.start or "", {})
    missing = [j for j in planned if j not in values]
    if missing and values:
        warnings.append(f"the start ({source}) has no {', '.join(missing)}: using the {defaults.start} pose for them")
    start = {j: float(values.get(j, fallback.get(j, 0.0))) for j in planned}
    return start, source, warnings


def urdf_limits(model_file: str | Path) -> dict[str, tuple[float, float]]:
    """{joint: (lower, upper)} of the URDF's revolute and prismatic joints ({} for other formats)."""
    path = Path(model_file)
    if path.suffix.lower() != ".urdf":
        return {}
    out = {}
    for joint in ET.parse(path).getroot().iter("joint"):
        limit = joint.find("limit")
        if joint.get("type") in ("revolute", "prismatic") and limit is not None:
            out[joint.get("name")] = (float(limit.get("lower", "-inf")), float(limit.get("upper", "inf")))
    return out


def clamp_to_limits(start: dict[str, float], limits: dict[str, tuple[float, float]], source: str,
                    start_source: str) -> tuple[dict[str, float], list[str]]:
    """The start with values within LIMIT_TOLERANCE outside a limit clamped (one warning each).

    Args:
        start: joint -> value.
        limits: joint -> (lower, upper), e.g. from :func:`urdf_limits`.
        source: the file the start belongs to (every error begins with it).
        start_source: where the values came from ("the scene's robot_state", a named pose, ...).

    Raises:
        SceneError: a value further outside its limits (names the joint, value and limits).
    """
    out, warnings = dict(start), []
    for joint, value in start.items():
        if joint not in limits:
            continue
        lo, hi = limits[joint]
        if lo <= value <= hi:
            continue
        if lo - LIMIT_TOLERANCE <= value <= hi + LIMIT_TOLERANCE:
            out[joint] = min(max(value, lo), hi)
            warnings.append(f"start {joint} = {value:.3g} is just outside its limits [{lo:g}, {hi:g}]: clamped to {out[joint]:g}")
        else:
            raise SceneError(f"{source}: start {joint} = {value:g} ({start_source}) is outside its limits [{lo:g}, {hi:g}]")
    return out, warnings


def override_scene_start(scene, options: StartOptions):
    """``plan --start/--start-from/--start-joints``: the scene with its start replaced, and warnings.

    Raises:
        SceneError: the robot has no robot.yaml (no named poses, no planned joints to fill),
            or any error of :func:`resolve_start` / :func:`clamp_to_limits`.
    """
    from dataclasses import replace

    from lazyground.robots.defaults import defaults_for_model

    if not options.given:
        return scene, []
    defaults = defaults_for_model(scene.robot.model) or RobotDefaults(model=scene.robot.model)
    planned = tuple(scene.robot.planned_joints or scene.robot.start)
    start, source, warnings = resolve_start(scene.robot.start, "the scene's start", options, defaults, planned)
    start, more = clamp_to_limits(start, urdf_limits(scene.robot.model), str(scene.source), source)
    return replace(scene, robot=replace(scene.robot, start={**scene.robot.start, **start})), warnings + more
