"""The scene schema: frozen dataclasses that a scene YAML file loads into.

See ``docs/scene_format.md`` for the documented format. No pydrake here: the
grounding module and the CLI's input checks use this without Drake.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from lazyground.geometry import Pose
from lazyground.typed_yaml import checked, in_range, positive
from lazyground.planner_spec import AlgorithmSpec, PlannerSpec  # noqa: F401  (the scene's planner block)
from lazyground.robots.defaults import AXES, EndEffectorSpec  # noqa: F401  (robot.yaml and scenes share it)
from lazyground.settings import BY_NAME

OBJECT_TYPES_HINT = "can, box, cup, bottle, table, shelf, parking_spot, ..."


@dataclass(frozen=True)
class PoseSpec:
    """``{xyz: [x, y, z], rpy: [roll, pitch, yaw]}``, metres and radians."""

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def pose(self) -> Pose:
        return Pose(self.xyz, self.rpy)


@dataclass(frozen=True)
class Cylinder:
    radius: float = checked(positive)
    length: float = checked(positive)


@dataclass(frozen=True)
class Sphere:
    radius: float = checked(positive)


@dataclass(frozen=True)
class MeshFile:
    """A mesh file (OBJ or STL; relative paths are relative to the scene file), scaled per axis.
    Drake collides with its convex hull."""

    file: str
    scale: tuple[float, float, float] = checked(positive, default=(1.0, 1.0, 1.0))

    def validate(self) -> str | None:
        if Path(self.file).suffix.lower() not in MESH_SUFFIXES:
            return f"file: {self.file!r}: mesh files must be {' or '.join(MESH_SUFFIXES)}"
        return None


MESH_SUFFIXES = (".obj", ".stl")
SHAPES = ("box", "cylinder", "sphere", "mesh")


@dataclass(frozen=True)
class Geometry:
    """Exactly one of ``box: [x, y, z]``, ``cylinder: {radius, length}``, ``sphere: {radius}``,
    ``mesh: {file, scale}`` (obstacles only)."""

    box: tuple[float, float, float] | None = checked(positive, default=None)
    cylinder: Cylinder | None = None
    sphere: Sphere | None = None
    mesh: MeshFile | None = None

    def validate(self) -> str | None:
        given = [k for k in SHAPES if getattr(self, k) is not None]
        if len(given) != 1:
            return f"shape: give exactly one of {', '.join(SHAPES)} (got {', '.join(given) or 'none'})"
        return None

    @property
    def kind(self) -> str:
        return next(k for k in SHAPES if getattr(self, k) is not None)

    def half_extents(self) -> tuple[float, float, float]:
        """Half sizes of the shape's axis-aligned box in its own frame."""
        if self.box:
            return (self.box[0] / 2, self.box[1] / 2, self.box[2] / 2)
        if self.cylinder:
            return (self.cylinder.radius, self.cylinder.radius, self.cylinder.length / 2)
        if self.mesh:  # typed objects cannot be meshes (Scene.validate); no caller needs a mesh's size
            raise ValueError("a mesh has no primitive extents")
        r = self.sphere.radius
        return (r, r, r)

    def contains(self, p_G, margin: float = 1e-9) -> bool | None:
        """Whether the point ``p_G`` (in the shape's own frame) lies strictly inside the shape; None for a mesh."""
        if self.mesh:
            return None
        x, y, z = (float(v) for v in p_G)
        if self.box:
            return all(abs(v) < h - margin for v, h in zip((x, y, z), self.half_extents()))
        if self.cylinder:
            return math.hypot(x, y) < self.cylinder.radius - margin and abs(z) < self.cylinder.length / 2 - margin
        return math.sqrt(x * x + y * y + z * z) < self.sphere.radius - margin

    def volume(self) -> float:
        if self.box:
            return self.box[0] * self.box[1] * self.box[2]
        if self.cylinder:
            return math.pi * self.cylinder.radius**2 * self.cylinder.length
        return 4 / 3 * math.pi * self.sphere.radius**3


@dataclass(frozen=True)
class Obstacle:
    id: str
    geometry: Geometry
    pose: PoseSpec = PoseSpec()
    color: str | None = None


@dataclass(frozen=True)
class SceneObject:
    """A semantically typed object: what requests talk about."""

    id: str
    type: str
    geometry: Geometry
    pose: PoseSpec = PoseSpec()
    color: str | None = None
    size: str | None = None
    occupied: bool = False
    collision: bool | None = None  # default: every type but parking_spot collides
    occupant: Geometry | None = None  # what an occupied object holds (default: its type's `occupant` in lazyground/scene/types.yaml)
    attributes: dict[str, str] = field(default_factory=dict)

    @property
    def collides(self) -> bool:
        if self.collision is not None:
            return self.collision
        return self.type != "parking_spot"


@dataclass(frozen=True)
class ToolSpec:
    """A tool (a gripper from its own package) mounted on a robot frame: ``{model: FILE, parent: tool0, pose: {...}}``."""

    model: str  # a URDF or .urdf.xacro file (relative to the scene), or a bundled name
    parent: str  # the robot link it is fixed to (e.g. the flange, tool0)
    pose: PoseSpec = PoseSpec()  # of the tool's root link in the parent link
    xacro_args: dict[str, str | bool | int | float] = field(default_factory=dict)


@dataclass(frozen=True)
class RobotSpec:
    """The robot: a model file, its planned joints and its start configuration."""

    model: str
    # {joint: value}; or a named pose ("tucked"); or {from: NAME, joint: value, ...} (overrides);
    # None = the robot.yaml's start. The loader leaves a {joint: value} mapping (robots/complete.py).
    start: dict[str, float | str] | str | None = None
    base: PoseSpec | None = None  # weld pose of the model's base link; None = free/planar models
    base_link: str | None = None  # None = the robot.yaml's, else "base_link"
    planned_joints: tuple[str, ...] | None = None  # None = the robot.yaml's, else every movable joint
    limits: dict[str, tuple[float, float]] = field(default_factory=dict)  # per position name
    weights: dict[str, float] = field(default_factory=dict)  # per position name, for the metric
    # a frame name (x approach, y closing unless it is the robot.yaml's frame) or the full spec
    end_effector: str | EndEffectorSpec | None = None
    packages: dict[str, str] = field(default_factory=dict)  # package:// NAME -> folder (relative to the scene)
    srdf: str | None = None  # MoveIt SRDF: disable_collisions pairs and group_state named poses
    allowed_collisions: tuple[tuple[str, str], ...] = ()  # link pairs never checked against each other
    xacro_args: dict[str, str | bool | int | float] = field(default_factory=dict)  # a .xacro model's arg values
    tools: tuple[ToolSpec, ...] = ()  # grippers from their own packages, mounted on the arm (the end effector from theirs)

    def validate(self) -> str | None:
        for name, (lo, hi) in self.limits.items():
            if not lo < hi:
                return f"limits: {name}: lower {lo:g} must be below upper {hi:g}"
        for name, w in self.weights.items():
            if w <= 0:
                return f"weights: {name}: must be > 0, got {w:g}"
        return None


@dataclass(frozen=True)
class Expectation:
    """What a regression test asserts for one request on this scene."""

    request: str
    interpretations: tuple[str, ...] | None = None  # exact set of interpretation ids
    success_rate: float = checked(in_range(0.0, 1.0), default=0.9)
    seeds: int = checked(positive, default=10)
    time_limit: float | None = checked(positive, default=None)
    strategy: str | None = checked(BY_NAME["strategy"].problem, default=None)
    algorithm: str | None = checked(BY_NAME["algorithm"].problem, default=None)
    goal_bias: float | None = checked(BY_NAME["goal_bias"].problem, default=None)
    reachable: tuple[str, ...] | None = None  # objects a solution may reach; None = any
    # per planning run: the outcome of a seed then depends on nothing else, not on the machine's load
    # (time_limit becomes a backstop); tests/scenes requires it in every bundled scene
    max_iterations: int | None = checked(positive, default=None)


@dataclass(frozen=True)
class Scene:
    name: str
    robot: RobotSpec
    description: str = ""
    obstacles: tuple[Obstacle, ...] = ()
    objects: tuple[SceneObject, ...] = ()
    planner: PlannerSpec = PlannerSpec()
    expect: tuple[Expectation, ...] = ()
    grasp_types: dict[str, dict] | None = None  # per-type overrides of lazyground/scene/types.yaml
    # "pick up two cans" with one gripper (#30): the surfaces every object but the last is put down on
    # (object ids); none: any surface other than the one the object came from (docs/requests.md)
    stow: tuple[str, ...] = ()
    source: str = ""  # file the scene came from (set by the loader)

    def validate(self) -> str | None:
        seen: dict[str, str] = {}
        for kind, items in (("obstacles", self.obstacles), ("objects", self.objects)):
            for i, item in enumerate(items):
                if not item.id.strip():
                    return f"{kind}[{i}].id: must not be empty"
                if item.id in seen:
                    return f"{kind}[{i}].id: duplicate id {item.id!r} (also in {seen[item.id]})"
                seen[item.id] = kind
        for i, obj in enumerate(self.objects):
            if obj.geometry.mesh is not None:
                return f"objects[{i}].geometry.mesh: {obj.id!r}: meshes can only be obstacles"
        for i, name in enumerate(self.stow):
            if seen.get(name) != "objects":
                return f"stow[{i}]: {name!r} is no object of the scene (a surface to put things down on)"
        return None

    def object(self, object_id: str) -> SceneObject:
        for obj in self.objects:
            if obj.id == object_id:
                return obj
        raise KeyError(object_id)

    def objects_of_type(self, type_name: str) -> list[SceneObject]:
        return [o for o in self.objects if o.type == type_name]
