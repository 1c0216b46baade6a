"""Is a scene's start free, and which of the robot's named poses are (#15)?"""

from __future__ import annotations

import numpy as np

from lazyground.robots.defaults import defaults_for_model


def named_pose_q(world, pose: dict[str, float]) -> np.ndarray:
    """The planned configuration of a named pose (joints it leaves out keep the start's values)."""
    q = np.array(world.start, float)
    for i, name in enumerate(world.space.names):
        if name in pose:
            q[i] = pose[name]
    return q


def free_named_poses(world) -> list[str]:
    """The robot's named poses that are collision-free in this world."""
    defaults = defaults_for_model(world.scene.robot.model)
    if defaults is None:
        return []
    return [name for name, pose in defaults.named_poses.items() if world.config_free(named_pose_q(world, pose))]


def start_collision_message(scene, start_source: str, world=None) -> str | None:
    """None when the scene's start is free; else one line naming the colliding pairs and the free named poses."""
    if world is None:
        from lazyground.drake.world import DrakeWorld

        world = DrakeWorld(scene, visual=False)
    if world.config_free(world.start):
        return None
    free = free_named_poses(world)
    hint = f"free named poses: {', '.join(free)} (use --start NAME)" if free else "no named pose of the robot is free either"
    return f"the start ({start_source}) is in collision: {world.explain(world.start)}; {hint}, or --start-from REQUEST.yaml / --start-joints"


def start_hint(scene) -> str:
    """For ``plan`` when the start is in collision: the robot's free named poses, as one line."""
    from lazyground.drake.world import DrakeWorld

    free = free_named_poses(DrakeWorld(scene, visual=False))
    return f"free named poses: {', '.join(free)} (plan ... --start NAME)" if free else "no named pose of the robot is free here"
