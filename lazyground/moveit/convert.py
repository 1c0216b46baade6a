"""A MoveIt planning-scene mapping -> a lazyground scene mapping (#15). No pydrake, no files
written here (lazyground.moveit.importer does that).

Reads ``world.collision_objects`` (box ``[x, y, z]``, cylinder ``[height, radius]``, sphere
``[radius]``, a cone ``[height, radius]`` as its bounding cylinder, meshes by file; ``primitive_poses``/``mesh_poses`` with xyzw quaternions,
composed with the object's ``pose``) and the start (``robot_state.joint_state``, or the
start options). The robot block spells out the robot.yaml's base link, planned joints and
end-effector frame; no planner block is written, so the robot.yaml's planner settings apply
(lazyground.scene.robot_fill).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lazyground.geometry import Pose, matrix_to_rpy, quaternion_xyzw_to_matrix
from lazyground.scene.file_kind import FileKind, kind_of_mapping, not_a_scene_message
from lazyground.moveit.meshes import MeshLookup, MeshTally, find_mesh
from lazyground.moveit.start import StartOptions, clamp_to_limits, joint_state_values, resolve_start, urdf_limits
from lazyground.moveit.types import OBSTACLE, UserRule, classify
from lazyground.robots.defaults import RobotDefaults, defaults_for_model
from lazyground.scene.loader import resolve_model
from lazyground.typed_yaml import SceneError

SHAPES = {1: "box", 2: "sphere", 3: "cylinder", 4: "cone"}
WORLD_FRAMES = ("", "world", "map", "odom")  # besides the robot's base link, welded at the world origin


@dataclass(frozen=True)
class ImportOptions:
    """How to import: the robot, user type rules, mesh packages, the start, the scene name."""

    robot: str = "fetch"
    user_rules: tuple[UserRule, ...] = ()
    packages: dict[str, Path] = field(default_factory=dict)
    start: StartOptions = StartOptions()
    name: str = "imported"
    srdf: str | None = None  # the robot's SRDF, written into the scene's robot block
    xacro_args: dict[str, str] = field(default_factory=dict)  # a .xacro robot's arguments, written likewise


@dataclass(frozen=True)
class ImportSummary:
    """What an import did, for the closing line and tests."""

    types: dict[str, int]  # imported primitives per type ("obstacle" = untyped)
    meshes_imported: int
    meshes_dropped: int
    objects: int  # collision objects in the source
    objects_dropped: int  # collision objects of which nothing was imported
    start_source: str
    warnings: tuple[str, ...]
    notes: tuple[str, ...]  # type decisions geometry overruled

    def line(self) -> str:
        kinds = ", ".join(f"{t} {n}" for t, n in sorted(self.types.items()))
        return (f"imported {sum(self.types.values())} geometries from {self.objects} collision objects ({kinds}); "
                f"meshes: {self.meshes_imported} imported, {self.meshes_dropped} dropped; start: {self.start_source}")


def robot_defaults(robot: str) -> tuple[RobotDefaults, Path]:
    """The robot.yaml of a bundled robot name or model path, and its model file.

    Raises:
        SceneError: no such robot, or it has no robot.yaml.
    """
    model = resolve_model(robot, None)
    defaults = defaults_for_model(model) if model is not None else None
    if defaults is None or defaults.planned_joints is None:
        raise SceneError(f"--robot {robot!r}: no robot model with a robot.yaml that lists planned_joints (e.g. fetch)")
    return defaults, model


def convert_moveit(data, source: str, options: ImportOptions = ImportOptions(), scene_dir: Path | None = None) -> tuple[dict, ImportSummary]:
    """A parsed MoveIt planning scene -> (scene mapping for the scene loader, summary).

    Raises:
        SceneError: not a planning scene (one line saying what it is), or a malformed object (naming its id).
    """
    kind = kind_of_mapping(data)
    if kind is not FileKind.PLANNING_SCENE:
        raise SceneError(f"{source}: {not_a_scene_message(kind, data)}")
    defaults, model = robot_defaults(options.robot)
    warnings: list[str] = []
    start, start_source = _start(data, source, options.start, defaults, model, warnings)
    world = data.get("world") or {}
    entries = world.get("collision_objects") or [] if isinstance(world, dict) else None
    if not isinstance(entries, list):
        raise SceneError(f"{source}: world.collision_objects: expected a list")
    lookup = MeshLookup(scene_dir or Path("."), dict(options.packages))
    frames = WORLD_FRAMES + (defaults.base_link,)
    opening = defaults.end_effector.opening if defaults.end_effector else None
    obstacles, objects, notes, dropped = [], [], [], Counter()
    meshes, seen = MeshTally(), {}
    for i, entry in enumerate(entries):
        oid = entry.get("id").strip() if isinstance(entry, dict) and isinstance(entry.get("id"), str) else ""
        where = f"{source}: collision object {oid!r}" if oid else f"{source}: world.collision_objects[{i}]"
        items = _convert_object(entry, oid, where, frames, lookup, warnings, meshes)
        if not items:
            dropped[oid] += 1
        for item, extents, shape in items:
            type_name, note = classify(item["id"], extents, shape, opening, options.user_rules)
            if note:
                notes.append(note)
            if item["id"] in seen:
                raise SceneError(f"{where}: duplicate id {item['id']!r} (also collision object {seen[item['id']]!r})")
            seen[item["id"]] = oid
            if type_name == OBSTACLE:
                obstacles.append({**item, **_colour(entry)})
            else:
                objects.append({"id": item["id"], "type": type_name, **{k: v for k, v in item.items() if k != "id"}})
    _mesh_warning(meshes, len(entries), dropped, warnings)
    if not obstacles and not objects:
        raise SceneError(f"{source}: no collision object could be imported ({len(entries)} in the file)")
    scene = {
        "name": options.name,
        "description": f"Imported from the MoveIt planning scene {Path(source).name}.",
        "robot": _robot_block(options.robot, start, options.srdf, options.xacro_args),
        "obstacles": obstacles,
        "objects": objects,
    }
    types = Counter(o["type"] for o in objects) + Counter({OBSTACLE: len(obstacles)})
    summary = ImportSummary(dict(types), meshes.imported, meshes.dropped, len(entries), sum(dropped.values()),
                            start_source, tuple(warnings), tuple(notes))
    return scene, summary


def _robot_block(robot: str, start: dict[str, float], srdf: str | None, xacro_args: dict[str, str]) -> dict:
    """The scene's robot block: the model welded at the origin (MoveIt scenes are in its base frame) and
    the start; base link, planned joints and end effector (with its axes) come from the robot.yaml."""
    block = {"model": robot, "base": {"xyz": [0.0, 0.0, 0.0]}, "start": start}
    if srdf is not None:
        block["srdf"] = str(Path(srdf).resolve())
    if xacro_args:
        block["xacro_args"] = dict(xacro_args)
    return block


def _start(data: dict, source: str, options: StartOptions, defaults: RobotDefaults, model: Path, warnings: list[str]):
    state = data.get("robot_state") if isinstance(data.get("robot_state"), dict) else {}
    base, base_source = {}, f"the robot's default pose {defaults.start!r}"
    if state.get("joint_state"):
        base = joint_state_values(state["joint_state"], f"{source}: robot_state.joint_state")
        base_source = "the scene's robot_state"
    elif not options.name and not options.request:
        warnings.append(f"no robot_state.joint_state: starting from {base_source}")
    start, start_source, more = resolve_start(base, base_source, options, defaults, tuple(defaults.planned_joints))
    warnings += more
    start, more = clamp_to_limits(start, urdf_limits(model), source, start_source)
    warnings += more
    return {j: _round(v) for j, v in start.items()}, start_source


def _mesh_warning(meshes: MeshTally, total: int, dropped: Counter, warnings: list[str]) -> None:
    if not meshes.dropped:
        return
    lost = sum(dropped.values())
    more = f" (+{len(meshes.reasons) - 3} more)" if len(meshes.reasons) > 3 else ""
    warnings.append(f"{meshes.dropped} mesh(es) not found or not importable, {lost} of {total} collision objects "
                    f"({100 * lost / max(total, 1):.0f}%) dropped: {'; '.join(meshes.reasons[:3])}{more}")


def _convert_object(entry, oid: str, where: str, frames, lookup: MeshLookup, warnings: list[str], meshes: MeshTally) -> list:
    """[(scene item, world extents, shape kind)] for one collision object."""
    if not oid:
        raise SceneError(f"{where}: expected a mapping with a non-empty id")
    operation = entry.get("operation", 0)
    if operation not in (0, "0", "add", "ADD", None):
        warnings.append(f"{oid}: operation {operation!r} is not an add: skipped")
        return []
    header = entry.get("header") or {}
    if not isinstance(header, dict):
        raise SceneError(f"{where}: header: expected a mapping with frame_id")
    frame = str(header.get("frame_id", "")).lstrip("/")
    if frame not in frames:
        raise SceneError(f"{where}: header.frame_id {frame!r} is not supported (use one of: {', '.join(f for f in frames if f)})")
    X_WO = _pose(entry["pose"], f"{where}: pose", oid, warnings) if entry.get("pose") else Pose()
    if entry.get("planes"):
        n = len(entry["planes"]) if isinstance(entry["planes"], list) else 1
        warnings.append(f"{oid}: {n} plane(s) skipped (planes are not supported; model a floor from a box)")
    out = []
    for shapes_key, poses_key, convert in (("primitives", "primitive_poses", _primitive), ("meshes", "mesh_poses", _mesh)):
        shapes, poses = entry.get(shapes_key) or [], entry.get(poses_key) or []
        if not isinstance(shapes, list) or not isinstance(poses, list) or len(shapes) != len(poses):
            raise SceneError(f"{where}: {shapes_key} and {poses_key} must be lists of equal length")
        for k, (shape, pose) in enumerate(zip(shapes, poses)):
            out.append((shapes_key, k, shape, pose, convert))
    items = []
    for shapes_key, k, shape, pose, convert in out:
        pid = oid if len(out) == 1 else f"{oid}_{len(items) + 1}"
        converted = convert(shape, f"{where}: {shapes_key}[{k}]", pid, lookup, warnings, meshes)
        if converted is None:
            continue
        geometry, local_extents = converted
        X = X_WO.compose(_pose(pose, f"{where}: {shapes_key.rstrip('s') if shapes_key == 'meshes' else 'primitive'}_poses[{k}]", pid, warnings))
        extents = tuple(float(v) for v in np.abs(X.rotation()) @ np.asarray(local_extents))
        item = {"id": pid, "geometry": geometry, "pose": {"xyz": [_round(v) for v in X.xyz], "rpy": [_round(v) for v in X.rpy]}}
        items.append((item, extents, next(iter(geometry))))
    if not out and not entry.get("planes"):
        warnings.append(f"{oid}: no primitives or meshes: skipped")
    return items


def _primitive(prim, where: str, pid: str, lookup, warnings: list[str], meshes: MeshTally) -> tuple[dict, tuple] | None:
    if not isinstance(prim, dict):
        raise SceneError(f"{where}: expected a mapping with type and dimensions")
    kind = prim.get("type")
    kind = SHAPES.get(kind, kind) if isinstance(kind, int) else str(kind).lower()
    dims = prim.get("dimensions")
    if not isinstance(dims, list):
        raise SceneError(f"{where}: dimensions: expected a list")
    dims = [_number(d, f"{where}: dimensions") for d in dims]
    need = {"box": 3, "cylinder": 2, "sphere": 1, "cone": 2}
    if kind not in need:
        warnings.append(f"{pid}: primitive type {prim.get('type')!r} is not supported: skipped")
        return None
    if len(dims) < need[kind] or any(d <= 0 for d in dims[: need[kind]]):
        raise SceneError(f"{where}: a {kind} needs {need[kind]} positive dimension(s), got {dims}")
    if kind == "box":
        return {"box": [_round(d) for d in dims[:3]]}, tuple(dims[:3])
    if kind == "cone":
        warnings.append(f"{pid}: a cone: imported as its bounding cylinder (collides a little early near the tip)")
        kind = "cylinder"
    if kind == "cylinder":  # MoveIt: [height, radius]
        return {"cylinder": {"radius": _round(dims[1]), "length": _round(dims[0])}}, (2 * dims[1], 2 * dims[1], dims[0])
    return {"sphere": {"radius": _round(dims[0])}}, (2 * dims[0],) * 3


def _mesh(mesh, where: str, pid: str, lookup: MeshLookup, warnings: list[str], meshes: MeshTally) -> tuple[dict, tuple] | None:
    if not isinstance(mesh, dict):
        raise SceneError(f"{where}: expected a mapping")
    resource = mesh.get("resource")
    # a moveit_msgs/Mesh with inline triangles and vertices has no resource
    path, reason = find_mesh(resource, lookup) if isinstance(resource, str) else (None, "inline mesh data is not imported")
    if path is None:
        meshes.drop(f"{pid}: {reason}")
        return None
    scale = mesh.get("dimensions") or mesh.get("scale") or [1.0, 1.0, 1.0]
    scale = [_number(s, f"{where}: dimensions") for s in (scale if isinstance(scale, list) else [scale] * 3)]
    if len(scale) != 3 or any(s <= 0 for s in scale):
        raise SceneError(f"{where}: dimensions (scale): expected 3 positive numbers, got {scale}")
    meshes.imported += 1
    return {"mesh": {"file": str(path), "scale": scale}}, (0.0, 0.0, 0.0)  # extents unused: meshes are obstacles


def _colour(entry) -> dict:
    """``{"color": "#rrggbb"}`` of an object's RGBA colour (a ``.scene`` file's), or nothing."""
    rgba = entry.get("color") if isinstance(entry, dict) else None
    if not isinstance(rgba, list) or len(rgba) != 4 or not all(isinstance(c, (int, float)) for c in rgba):
        return {}
    return {"color": "#" + "".join(f"{round(min(max(float(c), 0.0), 1.0) * 255):02x}" for c in rgba[:3])}


def _pose(pose, where: str, pid: str, warnings: list[str]) -> Pose:
    """A geometry_msgs/Pose mapping (position, orientation xyzw) as a Pose; normalises quaternions."""
    if not isinstance(pose, dict):
        raise SceneError(f"{where}: expected a mapping with position and orientation")
    p = _vector(pose.get("position", [0.0, 0.0, 0.0]), ("x", "y", "z"), f"{where}.position")
    q = _vector(pose.get("orientation", [0.0, 0.0, 0.0, 1.0]), ("x", "y", "z", "w"), f"{where}.orientation")
    norm = float(np.linalg.norm(q))
    if norm < 1e-9:
        raise SceneError(f"{where}.orientation: zero quaternion")
    if abs(norm - 1.0) > 1e-6:
        warnings.append(f"{pid}: orientation quaternion has norm {norm:.6f}: normalised")
        q = [v / norm for v in q]
    rpy = matrix_to_rpy(quaternion_xyzw_to_matrix(q))
    return Pose(tuple(p), tuple(float(a) for a in rpy))


def _vector(value, keys: tuple[str, ...], where: str) -> list[float]:
    """A list [x, y, z(, w)] or a mapping {x:, y:, ...} of numbers."""
    if isinstance(value, dict):
        value = [value.get(k, 1.0 if k == "w" else 0.0) for k in keys]
    if not isinstance(value, list) or len(value) != len(keys):
        raise SceneError(f"{where}: expected {len(keys)} numbers")
    return [_number(v, where) for v in value]


def _number(value, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SceneError(f"{where}: expected a finite number, got {value!r}")
    return float(value)


def _round(v: float) -> float:
    return round(float(v), 9) + 0.0  # + 0.0 turns -0.0 into 0.0
