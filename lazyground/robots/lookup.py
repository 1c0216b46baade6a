"""Which robot a command means: a bundled name (``panda``) or a model path, with its robot.yaml.

``import_spec(robot)`` is what ``lazyground import-moveit --robot NAME|PATH`` writes into the
imported scene's robot block, read from the robot's ``robot.yaml`` (no table of robots in the
importer). No pydrake.
"""

from __future__ import annotations

from pathlib import Path

from lazyground.robots.defaults import defaults_for_model
from lazyground.scene.loader import resolve_model
from lazyground.scene.typed_yaml import SceneError

WORLD_FRAMES = ("", "world", "map", "odom")  # MoveIt frames taken as the world (the base is welded at its origin)


def import_spec(robot: str, source: str) -> dict:
    """The importer's robot description for ``robot`` (a bundled name or a URDF/SDF path).

    Returns:
        ``model``, ``base``, ``base_link``, ``planned_joints``, ``end_effector``, ``default_start``
        (the robot.yaml's start pose over the planned joints), ``planner`` and ``frames``.
    Raises:
        SceneError: no such model, or no robot.yaml beside it with planned joints and a start.
    """
    model = resolve_model(robot, Path.cwd())
    defaults = defaults_for_model(model) if model is not None else None
    if defaults is None or defaults.planned_joints is None or defaults.start is None:
        raise SceneError(f"{source}: unknown robot {robot!r}: no robot model with a robot.yaml that gives planned_joints and a start "
                         "(bundled: fetch, panda, ur5e)")
    pose = defaults.named_poses[defaults.start]
    return {
        "model": robot if model.parent.name == robot else str(model),
        "base": {"xyz": [0.0, 0.0, 0.0]},
        "base_link": defaults.base_link,
        "planned_joints": list(defaults.planned_joints),
        "end_effector": defaults.end_effector.frame if defaults.end_effector else None,
        "default_start": [pose.get(j, 0.0) for j in defaults.planned_joints],
        "planner": dict(defaults.planner),
        "frames": WORLD_FRAMES + (defaults.base_link,),
    }
