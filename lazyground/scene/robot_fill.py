"""A scene's planner settings layered over its robot's (#15).

Planner settings layer as robot.yaml ``planner`` < the scene's ``planner:`` block <
``per_algorithm`` < CLI/API overrides (the last two in ``lazyground.settings.from_scene``),
key by key: a scene without a ``planner:`` block (every imported MoveIt scene) plans with
the robot's settings; a key the scene sets at the top of its block also beats the robot's
``per_algorithm`` value for it (the scene's choice is the more specific). The robot.yaml's
block is checked by the same declarations when it is read (robots/defaults.py).
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

from lazyground.robots.defaults import defaults_for_model


def fill_from_robot_defaults(data, resolve: Callable[[str], Path | None]):
    """The scene mapping with the robot's planner settings under its own (``data`` itself when there are none).

    Args:
        data: the parsed scene YAML (anything; non-mappings are returned for the strict loader to reject).
        resolve: model name or path -> model file (None when not found).

    Raises:
        SceneError: the robot.yaml is invalid.
    """
    robot = data.get("robot") if isinstance(data, dict) else None
    if not isinstance(robot, dict) or not isinstance(robot.get("model"), str):
        return data
    model = resolve(robot["model"])
    defaults = defaults_for_model(model) if model is not None else None
    if defaults is None or not defaults.planner:
        return data
    return {**data, "planner": merge_planner(defaults.planner, data.get("planner"))}


def merge_planner(robot: dict, scene) -> dict:
    """The robot's planner block under the scene's (a non-mapping scene block is left for the loader to reject)."""
    if scene is None:
        return dict(robot)
    if not isinstance(scene, dict):
        return scene
    per_scene = scene.get("per_algorithm") or {}
    if not isinstance(per_scene, dict):
        return {**robot, **scene}
    per = {}
    for name, values in (robot.get("per_algorithm") or {}).items():
        per[name] = {k: v for k, v in values.items() if k not in scene}
    for name, values in per_scene.items():
        per[name] = {**per.get(name, {}), **values} if isinstance(values, dict) else values
    merged = {**robot, **scene}
    per = {k: v for k, v in per.items() if v != {}}
    if per:
        merged["per_algorithm"] = per
    else:
        merged.pop("per_algorithm", None)
    return merged
