"""Import a MoveIt planning scene (YAML) as a lazyground scene.

    warnings = import_moveit_file("scene.yml", "fetch", "yaml_scenes/mine.yaml")

Reads ``world.collision_objects`` (box ``[x, y, z]``, cylinder ``[height,
radius]``, sphere ``[radius]``; ``primitive_poses`` with xyzw quaternions,
composed with the object's ``pose`` when given) and the start joint state
(``robot_state.joint_state``). Object types come from id prefixes by
:data:`TYPE_RULES` (first match wins; unmatched ids become obstacles); pass
``rules`` to extend it. No pydrake here.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import yaml

from lazyground.geometry import Pose, matrix_to_rpy, quaternion_xyzw_to_matrix
from lazyground.robots.lookup import import_spec
from lazyground.scene.loader import load_scene
from lazyground.scene.typed_yaml import SceneError

# (id prefix, type), matched case-insensitively in order; "obstacle" = untyped obstacle.
TYPE_RULES: tuple[tuple[str, str], ...] = (
    ("Can", "can"),
    ("Box", "box"),
    ("Cube", "box"),
    ("Shelf", "shelf"),
    ("Table", "table"),
    ("Bottle", "bottle"),
    ("Cup", "cup"),
    ("Mug", "cup"),
    ("Counter", "counter"),
    ("Cabinet", "cabinet"),
    ("Bar", "obstacle"),
    ("Cylinder", "obstacle"),
    ("Wall", "obstacle"),
)

# Per robot: the scene's robot block, without the start (filled from the joint state).
ROBOTS: dict[str, dict] = {
    "fetch": {
        "model": "fetch",
        "base": {"xyz": [0.0, 0.0, 0.0]},
        "base_link": "base_link",
        "planned_joints": [
            "torso_lift_joint", "shoulder_pan_joint", "shoulder_lift_joint", "upperarm_roll_joint",
            "elbow_flex_joint", "forearm_roll_joint", "wrist_flex_joint", "wrist_roll_joint",
        ],
        "end_effector": "gripper_link",
        "default_start": [0.05, 1.32, 1.4, -0.2, 1.72, 0.0, 1.66, 0.0],
        "planner": {"collision_padding": 0.005, "step_size": 0.5},
        "frames": ("", "world", "base_link", "map", "odom"),  # base_link is welded at the world origin
    },
}

SHAPES = {1: "box", 2: "sphere", 3: "cylinder", 4: "cone"}


def object_type(object_id: str, rules=TYPE_RULES) -> str:
    """The type of an object from its id prefix (case-insensitive); "obstacle" when none matches."""
    for prefix, type_name in rules:
        if object_id.lower().startswith(prefix.lower()):
            return type_name
    return "obstacle"


def import_moveit_file(path, robot: str, output, rules=None, name: str | None = None, srdf: str | None = None) -> list[str]:
    """Convert a MoveIt planning-scene YAML file into a lazyground scene file.

    Args:
        path: the MoveIt scene (``.yml``/``.yaml``).
        robot: the robot the scene is for (known: the keys of :data:`ROBOTS`).
        output: the scene file to write.
        rules: (prefix, type) pairs tried before :data:`TYPE_RULES`.
        name: the scene name (default: the output file's stem).
        srdf: a MoveIt SRDF for the robot block (disabled pairs, named poses).

    Returns:
        Warnings, one line each (skipped meshes, normalised quaternions, ...).

    Raises:
        SceneError: unreadable or malformed input, or an output that does not load.
    """
    path, output = Path(path), Path(output)
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise SceneError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark else ""
        raise SceneError(f"{path}: YAML syntax error{where}: {getattr(exc, 'problem', None) or 'invalid YAML'}") from None
    except UnicodeDecodeError:
        raise SceneError(f"{path}: not a UTF-8 text file") from None
    all_rules = tuple(rules or ()) + TYPE_RULES
    scene, warnings = convert_moveit(data, robot, str(path), all_rules, name or output.stem)
    if srdf:
        scene["robot"]["srdf"] = str(Path(srdf).resolve())
    text = f"# Imported from {path.name} by `lazyground import-moveit`.\n" + yaml.safe_dump(scene, sort_keys=False, default_flow_style=None, width=120)
    try:
        output.write_text(text, encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"{output}: cannot write: {exc.strerror or exc}") from None
    load_scene(output)  # the output must load; a SceneError here names the output file
    return warnings


def convert_moveit(data, robot: str, source: str, rules=TYPE_RULES, name: str = "imported") -> tuple[dict, list[str]]:
    """A MoveIt planning-scene mapping → (scene mapping for :func:`load_scene`, warnings)."""
    if not isinstance(data, dict):
        raise SceneError(f"{source}: expected a MoveIt planning scene mapping at the top level")
    spec = ROBOTS[robot] if robot in ROBOTS else import_spec(robot, source)  # any robot with a robot.yaml
    warnings: list[str] = []
    start = _start(data, spec, source, warnings)
    world = data.get("world") or {}
    if not isinstance(world, dict):
        raise SceneError(f"{source}: world: expected a mapping")
    entries = world.get("collision_objects") or []
    if not isinstance(entries, list):
        raise SceneError(f"{source}: world.collision_objects: expected a list")
    obstacles, objects = [], []
    for i, entry in enumerate(entries):
        for item in _convert_object(entry, f"{source}: world.collision_objects[{i}]", spec, rules, warnings):
            (obstacles if item.pop("_type") == "obstacle" else objects).append(item)
    seen: set[str] = set()
    for item in obstacles + objects:
        if item["id"] in seen:
            raise SceneError(f"{source}: world.collision_objects: duplicate id {item['id']!r}")
        seen.add(item["id"])
    robot_block = {k: spec[k] for k in ("model", "base", "base_link", "planned_joints", "end_effector")}
    robot_block = {**robot_block, "start": start}
    scene = {
        "name": name,
        "description": f"Imported from the MoveIt planning scene {Path(source).name}.",
        "robot": robot_block,
        "obstacles": obstacles,
        "objects": objects,
        "planner": dict(spec["planner"]),
    }
    return scene, warnings


def _start(data: dict, spec: dict, source: str, warnings: list[str]) -> dict[str, float]:
    """Planned joints' start values from robot_state.joint_state (default pose where missing)."""
    start = dict(zip(spec["planned_joints"], spec["default_start"]))
    state = (data.get("robot_state") or {}).get("joint_state") if isinstance(data.get("robot_state") or {}, dict) else None
    if not state:
        warnings.append(f"no robot_state.joint_state: using the default start pose of {spec['model']}")
        return start
    names, positions = state.get("name") or [], state.get("position") or []
    if not isinstance(names, list) or not isinstance(positions, list) or len(names) != len(positions):
        raise SceneError(f"{source}: robot_state.joint_state: name and position must be lists of equal length")
    given = {}
    for n, p in zip(names, positions):
        given[str(n)] = _number(p, f"{source}: robot_state.joint_state.position ({n})")
    missing = [j for j in spec["planned_joints"] if j not in given]
    if missing:
        warnings.append(f"robot_state.joint_state has no {', '.join(missing)}: using the default start for them")
    start.update({j: given[j] for j in spec["planned_joints"] if j in given})
    return start


def _convert_object(entry, where: str, spec: dict, rules, warnings: list[str]) -> list[dict]:
    if not isinstance(entry, dict) or not isinstance(entry.get("id"), str) or not entry["id"].strip():
        raise SceneError(f"{where}: expected a mapping with a non-empty id")
    oid = entry["id"].strip()
    operation = entry.get("operation", 0)
    if operation not in (0, "0", "add", "ADD", None):
        warnings.append(f"{oid}: operation {operation!r} is not an add: skipped")
        return []
    frame = str((entry.get("header") or {}).get("frame_id", "")).lstrip("/")
    if frame not in spec["frames"]:
        raise SceneError(f"{where} ({oid}): header.frame_id {frame!r} is not supported (use one of: {', '.join(f for f in spec['frames'] if f)})")
    X_WO = _pose(entry["pose"], f"{where} ({oid}).pose", oid, warnings) if entry.get("pose") else Pose()
    for kind, one in (("meshes", "mesh"), ("planes", "plane")):
        if entry.get(kind):
            n = len(entry[kind])
            warnings.append(f"{oid}: {n} {one if n == 1 else kind} skipped ({kind} are not supported; model it from primitives)")
    primitives = entry.get("primitives") or []
    poses = entry.get("primitive_poses") or []
    if not isinstance(primitives, list) or not isinstance(poses, list) or len(primitives) != len(poses):
        raise SceneError(f"{where} ({oid}): primitives and primitive_poses must be lists of equal length")
    type_name = object_type(oid, rules)
    out = []
    for k, (prim, pose) in enumerate(zip(primitives, poses)):
        pid = oid if len(primitives) == 1 else f"{oid}_{k + 1}"
        geometry = _geometry(prim, f"{where} ({oid}).primitives[{k}]", pid, warnings)
        if geometry is None:
            continue
        X = X_WO.compose(_pose(pose, f"{where} ({oid}).primitive_poses[{k}]", pid, warnings))
        item = {"id": pid}
        if type_name != "obstacle":
            item["type"] = type_name
        item["geometry"] = geometry
        item["pose"] = {"xyz": [_round(v) for v in X.xyz], "rpy": [_round(v) for v in X.rpy]}
        item["_type"] = type_name
        out.append(item)
    if not out and not entry.get("meshes") and not entry.get("planes"):
        warnings.append(f"{oid}: no primitives: skipped")
    return out


def _geometry(prim, where: str, pid: str, warnings: list[str]) -> dict | None:
    if not isinstance(prim, dict):
        raise SceneError(f"{where}: expected a mapping with type and dimensions")
    kind = prim.get("type")
    kind = SHAPES.get(kind, kind) if isinstance(kind, int) else str(kind).lower()
    dims = prim.get("dimensions")
    if not isinstance(dims, list):
        raise SceneError(f"{where}: dimensions: expected a list")
    dims = [_number(d, f"{where}.dimensions") for d in dims]
    need = {"box": 3, "cylinder": 2, "sphere": 1}
    if kind not in need:
        warnings.append(f"{pid}: primitive type {prim.get('type')!r} is not supported: skipped")
        return None
    if len(dims) < need[kind] or any(d <= 0 for d in dims[: need[kind]]):
        raise SceneError(f"{where}: a {kind} needs {need[kind]} positive dimension(s), got {dims}")
    if kind == "box":
        return {"box": [_round(d) for d in dims[:3]]}
    if kind == "cylinder":  # MoveIt: [height, radius]
        return {"cylinder": {"radius": _round(dims[1]), "length": _round(dims[0])}}
    return {"sphere": {"radius": _round(dims[0])}}


def _pose(pose, where: str, pid: str, warnings: list[str]) -> Pose:
    """A geometry_msgs/Pose mapping (position, orientation xyzw) as a Pose; normalises quaternions."""
    if not isinstance(pose, dict):
        raise SceneError(f"{where}: expected a mapping with position and orientation")
    p = pose.get("position", [0.0, 0.0, 0.0])
    q = pose.get("orientation", [0.0, 0.0, 0.0, 1.0])
    p = _vector(p, ("x", "y", "z"), f"{where}.position")
    q = _vector(q, ("x", "y", "z", "w"), f"{where}.orientation")
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
