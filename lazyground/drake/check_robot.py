"""``lazyground check-robot MODEL``: load a robot description and say what lazyground makes of it.

The first thing a user runs with their own robot: it loads the model as a scene would
(``package://`` resolution, STL/DAE meshes converted), welds its base, applies the SRDF's
disabled pairs, and reports the degrees of freedom, the joints with their limits, the
collision geometry per link, self-collisions at every named pose (robot.yaml and SRDF), what
is not supported, and a one-line verdict. Problems (exit 2) are what would stop planning: a
named pose in self-collision, outside the joint limits or naming unknown joints. Loading
failures (a missing mesh, an unknown package) raise ``SceneError`` with one line.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from pydrake.geometry import Role
from pydrake.planning import RobotDiagramBuilder, SceneGraphCollisionChecker

from lazyground.drake.coordinates import unbounded_positions
from lazyground.drake.robot_model import add_robot, allow_collisions, floating_link, weld_base
from lazyground.drake.self_collision import ALWAYS, DEFAULT_SAMPLES, sample_pairs
from lazyground.drake.self_collision import write_allowed as write_allowed_file
from lazyground.robots.defaults import defaults_for_model
from lazyground.robots.srdf import read_srdf
from lazyground.robots.tools import mimic_joints
from lazyground.typed_yaml import SceneError

PADDING = 0.0  # m: self-collision at named poses is reported at contact, as MoveIt does
CHECK_SAMPLES = 200  # configurations sampled for always-touching link pairs (a few hundred ms)


@dataclass(frozen=True)
class JointInfo:
    name: str
    kind: str
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    velocity: tuple[float, ...]


@dataclass(frozen=True)
class RobotCheck:
    """The report of :func:`check_robot`."""

    model: str
    base_link: str
    dof: int
    joints: tuple[JointInfo, ...]
    geometry: dict[str, dict[str, int]]  # link -> shape kind -> count (collision role)
    pose_collisions: dict[str, list[tuple[str, str]]]  # named pose -> colliding link pairs
    problems: tuple[str, ...]
    unsupported: tuple[str, ...]
    notes: tuple[str, ...] = ()
    converted_meshes: int = 0
    packages: dict[str, str] = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return not self.problems

    def verdict(self) -> str:
        """One line: ok, or the problems."""
        if self.ok:
            return (f"ok: {Path(self.model).name} loads with {self.dof} DOF, collision geometry on "
                    f"{sum(1 for g in self.geometry.values() if g)} links, {len(self.pose_collisions)} named poses free")
        return f"{len(self.problems)} problem(s): " + "; ".join(self.problems)

    def lines(self) -> list[str]:
        """The human report, verdict last."""
        out = [f"model: {self.model} (base {self.base_link})", f"DOF: {self.dof}", "joints:"]
        for j in self.joints:
            limits = ", ".join(f"[{lo:.4g}, {hi:.4g}]" for lo, hi in zip(j.lower, j.upper))
            speed = ", ".join(f"{v:.4g}" for v in j.velocity)
            out.append(f"  {j.name} ({j.kind}) limits {limits} velocity {speed}")
        out.append("collision geometry:")
        for link, shapes in self.geometry.items():
            out.append(f"  {link}: " + (", ".join(f"{n} {k}" for k, n in sorted(shapes.items())) or "none"))
        if self.converted_meshes:
            out.append(f"meshes: {self.converted_meshes} converted to OBJ")
        for name, folder in self.packages.items():
            out.append(f"package {name}: {folder}")
        out.append("named poses:" if self.pose_collisions or self.problems else "named poses: none")
        for name, pairs in self.pose_collisions.items():
            out.append(f"  {name}: " + ("free" if not pairs else "self-collision " + ", ".join(f"{a}-{b}" for a, b in pairs)))
        out += [f"note: {n}" for n in self.notes]
        out += [f"unsupported: {u}" for u in self.unsupported]
        out.append(self.verdict())
        return out


def check_robot(model: str | Path, srdf: str | Path | None = None, packages: dict[str, Path] | None = None,
                xacro_args: dict | None = None, write_allowed: str | Path | None = None, samples: int | None = None,
                seed: int = 0) -> RobotCheck:
    """Load ``model`` and check it (see module docstring).

    Args:
        model: a URDF, SDF or xacro file.
        xacro_args: ``arg`` values of a xacro file.
        write_allowed: write the pairs to stop checking (adjacent, always and never touching) to this
            file (.srdf, else YAML for robot.allowed_collisions); their always-touching pairs are then
            not problems.
        samples: configurations sampled for always-touching pairs (default CHECK_SAMPLES, or
            self_collision.DEFAULT_SAMPLES when writing); ``seed`` seeds them.
        srdf: a MoveIt SRDF (default: the robot.yaml's, if any).
        packages: package folders by name, for ``package://`` URIs.
    Returns:
        The report.
    Raises:
        SceneError: the model cannot be loaded (one line, naming the file and what to do).
    """
    model = Path(model).resolve()
    defaults = defaults_for_model(model)
    if srdf is None and defaults is not None and defaults.srdf:
        srdf = defaults.path(defaults.srdf)
    xacro_args = {**(defaults.xacro_args if defaults is not None else {}), **(xacro_args or {})}
    builder = RobotDiagramBuilder(time_step=0.0)
    plant = builder.plant()
    instance, prepared = add_robot(builder.parser(), model, packages, "check-robot", xacro_args)
    base = defaults.base_link if defaults is not None else "base_link"  # as a scene without robot.base_link
    if defaults is not None and not plant.HasBodyNamed(base, instance):
        raise SceneError(f"check-robot: {model}: no base link {base!r}")
    floating = floating_link(plant, instance, base)
    weld_note = weld_base(plant, instance, base, None, "check-robot")  # what plan does without robot.base
    base = f"{floating} welded at the origin" if floating else "none: the model joints itself to the world"
    problems: list[str] = []
    notes: list[str] = list(prepared.notes) + ([weld_note] if weld_note else [])
    unsupported = []
    mimic = mimic_joints(prepared.text, prepared.file_type)
    if mimic:
        notes.append(f"mimic joints follow their leader at the start and are not planned unless named: "
                     + ", ".join(f"{m.joint} = {m.multiplier:g} x {m.leader} + {m.offset:g}" for m in mimic))
    unsupported += [f"<{tag}> x{n} removed before loading (planning does not use it)" for tag, n in sorted(prepared.stripped.items())]
    poses = dict(defaults.named_poses) if defaults is not None else {}
    if srdf is not None:
        parsed = read_srdf(srdf)
        skipped = allow_collisions(builder.scene_graph(), plant, instance, parsed.disabled_collisions, str(srdf), strict=False)
        notes.append(f"SRDF {Path(srdf).name}: {len(parsed.disabled_collisions) - len(skipped)} disabled pairs applied, "
                     f"{len(parsed.named_poses)} named poses")
        if skipped:
            notes.append(f"SRDF pairs naming links not in the model, skipped: {len(skipped)} (e.g. {skipped[0][0]}-{skipped[0][1]})")
        unsupported += [f"SRDF <{tag}> x{n} read but not used" for tag, n in sorted(parsed.ignored.items())]
        poses.update(parsed.named_poses)
    diagram = builder.Build()
    plant = diagram.plant()
    checker = SceneGraphCollisionChecker(model=diagram, robot_model_instances=[instance], edge_step_size=0.05,
                                         env_collision_padding=PADDING, self_collision_padding=PADDING)
    joints = _joints(plant, instance)
    unbounded = unbounded_positions(plant, instance)
    if unbounded:  # planning refuses them without limits, which a scene may give: a note, not a problem
        notes.append(f"unbounded positions {', '.join(unbounded)} (no limits in the model): a scene that plans them "
                     f"must give robot.limits, e.g. limits: {{{unbounded[0]}: [lower, upper]}}")
    rng = np.random.default_rng(seed)
    n = samples or (DEFAULT_SAMPLES if write_allowed else CHECK_SAMPLES)
    counts = sample_pairs(checker, diagram, instance, n, rng, seed, mimic)
    always = counts.always()
    if write_allowed:
        written = write_allowed_file(write_allowed, plant.GetModelInstanceName(instance), counts)
        notes.append(f"wrote {written} allowed pairs ({len(counts.adjacent)} adjacent, {len(counts.default)} at the default pose, {len(always)} always, "
                     f"{len(counts.never())} never touching over {n} samples, seed {seed}) to {write_allowed}")
    elif always:
        problems.append(f"{len(always)} link pair(s) touch in at least {ALWAYS:.0%} of {n} sampled configurations "
                        f"(e.g. {always[0][0]}-{always[0][1]}), so nothing can plan: write the pairs to allow with "
                        "check-robot MODEL --write-allowed allowed.yaml (or .srdf)")
    collisions = {}
    for name, pose in poses.items():
        q, problem = _pose_vector(plant, instance, pose, name)
        if problem:
            problems.append(problem)
            continue
        pairs = _colliding_pairs(checker, q)
        collisions[name] = pairs
        if pairs:
            problems.append(f"named pose {name!r} self-collides: " + ", ".join(f"{a}-{b}" for a, b in pairs))
    return RobotCheck(str(model), base, plant.num_positions(instance), joints, _geometry(diagram, plant, instance),
                      collisions, tuple(problems), tuple(unsupported), tuple(notes), len(prepared.converted), dict(prepared.packages))


def _joints(plant, instance) -> tuple[JointInfo, ...]:
    out = []
    for index in plant.GetJointIndices(instance):
        joint = plant.get_joint(index)
        if joint.num_positions() == 0:
            continue
        out.append(JointInfo(joint.name(), joint.type_name(), tuple(joint.position_lower_limits()), tuple(joint.position_upper_limits()),
                             tuple(joint.velocity_upper_limits())))
    return tuple(out)


def _geometry(diagram, plant, instance) -> dict[str, dict[str, int]]:
    inspector = diagram.scene_graph().model_inspector()
    out = {}
    for body_index in plant.GetBodyIndices(instance):
        frame_id = plant.GetBodyFrameIdOrThrow(body_index)
        shapes = Counter(inspector.GetShape(g).__class__.__name__.lower() for g in inspector.GetGeometries(frame_id, Role.kProximity))
        out[plant.get_body(body_index).name()] = dict(shapes)
    return out


def _pose_vector(plant, instance, pose: dict[str, float], name: str) -> tuple[np.ndarray | None, str | None]:
    """The plant positions of a named pose (others at their defaults), or a problem line."""
    context = plant.CreateDefaultContext()
    q = plant.GetPositions(context).copy()
    for joint_name, value in pose.items():
        if not plant.HasJointNamed(joint_name, instance):
            return None, f"named pose {name!r}: no joint {joint_name!r} in the model"
        joint = plant.GetJointByName(joint_name, instance)
        if joint.num_positions() != 1:
            return None, f"named pose {name!r}: joint {joint_name!r} has {joint.num_positions()} positions"
        lo, hi = joint.position_lower_limits()[0], joint.position_upper_limits()[0]
        if not lo - 1e-9 <= value <= hi + 1e-9:
            return None, f"named pose {name!r}: {joint_name} = {value:g} is outside its limits [{lo:g}, {hi:g}]"
        q[joint.position_start()] = value
    return q, None


def _colliding_pairs(checker, q: np.ndarray) -> list[tuple[str, str]]:
    """Link pairs in contact at ``q`` (pairs the checker filters are not reported)."""
    if checker.CheckConfigCollisionFree(q):
        return []
    clearance = checker.CalcRobotClearance(q, 0.05)
    plant = checker.plant()
    pairs = set()
    for a, b, d in zip(clearance.robot_indices(), clearance.other_indices(), clearance.distances()):
        if d <= PADDING:
            pairs.add(tuple(sorted((plant.get_body(a).name(), plant.get_body(b).name()))))
    return sorted(pairs)

