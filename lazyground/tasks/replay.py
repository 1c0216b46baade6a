"""The scene each step of an outcome planned in (several objects, #30): objects placed by earlier steps
stand where they were put; the robot starts where the last step ended. Used by the several-object task,
its validator and the HTML replay; needs no world (the steps record their placements).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lazyground.scene.schema import PoseSpec, Scene
from lazyground.tasks.outcome import Outcome


def moved(scene: Scene, object_id: str, X_WO, q_end: np.ndarray, names: tuple[str, ...]) -> Scene:
    """``scene`` after a placement: the object at ``X_WO``, the robot starting at ``q_end``."""
    pose = PoseSpec(tuple(float(x) for x in X_WO.xyz), tuple(float(x) for x in X_WO.rpy))
    objects = tuple(replace(o, pose=pose) if o.id == object_id else o for o in scene.objects)
    start = {**(scene.robot.start or {}), **{n: float(v) for n, v in zip(names, q_end)}}
    return replace(scene, objects=objects, robot=replace(scene.robot, start=start))


def scenes_per_step(outcome: Outcome, scene: Scene) -> list[Scene]:
    """The scene each of ``outcome``'s steps planned in: objects placed by earlier steps where they were put."""
    out, current = [], scene
    for step in outcome.steps:
        out.append(current)
        if step.placement is not None and step.grasp is not None:
            current = moved(current, step.grasp.object_id, step.placement.X_WO, step.result.path[-1], outcome.joint_names)
    return out
