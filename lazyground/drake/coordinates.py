"""The configuration space of a plant: which positions are planned, their limits, wrapping, metric and start.

The planner sees only the planned coordinates; :meth:`Coordinates.full` puts
them back into the plant's position vector, the others held at the start.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from pydrake.multibody.tree import PlanarJoint, RevoluteJoint

from lazyground.planning.space import ConfigSpace
from lazyground.scene.schema import Scene
from lazyground.typed_yaml import SceneError


@dataclass(frozen=True)
class Coordinates:
    """The planned coordinates of a plant.

    Attributes:
        space: limits, wrapping and metric weights of the planned coordinates.
        planned: indices of the planned coordinates in the plant's position vector.
        q_full: the plant's position vector at the start (unplanned positions stay here).
        turns: per planned coordinate, whether it is a revolute joint's angle, where q + 2 pi k is the
            same configuration (goals prefer the nearest within the limits, planning/turns.py).
    """

    space: ConfigSpace
    planned: tuple[int, ...]
    q_full: np.ndarray
    turns: np.ndarray | None = None

    @property
    def start(self) -> np.ndarray:
        return self.q_full[list(self.planned)].copy()

    @cached_property  # (full runs before every collision check)
    def plans_all(self) -> bool:
        return self.planned == tuple(range(len(self.q_full)))

    def full(self, q: np.ndarray) -> np.ndarray:
        """The plant's position vector for planned coordinates ``q`` (rows or one vector)."""
        q = np.asarray(q, float)
        if self.plans_all:
            return q
        out = np.empty(q.shape[:-1] + self.q_full.shape)
        out[...] = self.q_full
        out[..., list(self.planned)] = q
        return out

    def plant_weights(self) -> np.ndarray:
        """Metric weights over every plant position (unplanned ones weigh 0)."""
        weights = np.zeros(len(self.q_full))
        weights[list(self.planned)] = self.space.weights
        return weights


def coordinates_from_plant(plant, robot, scene: Scene, mimic=()) -> Coordinates:
    """The planned coordinates of ``robot`` in ``plant`` as the scene's robot section selects them.

    Args:
        plant: a finalized MultibodyPlant.
        robot: the robot's ModelInstanceIndex.
        scene: the loaded scene (planned joints, limits, weights and start).
        mimic: the model's mimic joints (``Mimic``): a follower is not planned unless named, and
            starts at ``multiplier * leader + offset`` unless the start gives it.

    Returns:
        The coordinates; angles of planar and unbounded revolute joints wrap.

    Raises:
        SceneError: a named joint or position is not in the model, the start is outside
            the limits, nothing is planned, or a planned position is unbounded.
    """
    spec, source = scene.robot, scene.source
    names = list(plant.GetPositionNames(robot, add_model_instance_prefix=False, always_add_suffix=False))
    lower = plant.GetPositionLowerLimits().copy()
    upper = plant.GetPositionUpperLimits().copy()
    wrap, joint_of = _joint_layout(plant, robot)
    revolute = np.zeros(plant.num_positions(), bool)
    for ji in plant.GetJointIndices(robot):
        if isinstance(plant.get_joint(ji), RevoluteJoint):
            revolute[plant.get_joint(ji).position_start()] = True
    planned = spec.planned_joints
    if planned is not None:
        unknown = [j for j in planned if j not in joint_of and j not in names]
        if unknown:
            raise SceneError(f"{source}: robot.planned_joints: no joint {unknown[0]!r} in the model (joints: {', '.join(dict.fromkeys(joint_of))})")
    followers = {m.joint for m in mimic}
    idx = [i for i, n in enumerate(names) if (planned is None and joint_of[i] not in followers) or
           (planned is not None and (n in planned or joint_of[i] in planned))]
    if not idx:
        raise SceneError(f"{source}: robot: nothing to plan: no movable joint selected (robot.planned_joints)")
    for key in list(spec.start) + list(spec.limits) + list(spec.weights):
        if key not in names:
            raise SceneError(f"{source}: robot: no position {key!r} in the model (positions: {', '.join(names)})")
    for key, (lo, hi) in spec.limits.items():
        i = names.index(key)
        lower[i], upper[i] = lo, hi
    q_full = np.zeros(plant.num_positions())
    for key, v in spec.start.items():
        q_full[names.index(key)] = v
    for m in mimic:  # followers keep to their leader at the start (Drake ignores <mimic> in a continuous plant)
        if m.joint in names and m.leader in names and m.joint not in spec.start:
            q_full[names.index(m.joint)] = m.multiplier * q_full[names.index(m.leader)] + m.offset
    for i, v in enumerate(q_full):
        if not wrap[i] and not lower[i] - 1e-9 <= v <= upper[i] + 1e-9:
            raise SceneError(f"{source}: robot.start.{names[i]}: {v:g} is outside the joint limits [{lower[i]:g}, {upper[i]:g}]")
    for i in idx:
        if not wrap[i] and not (np.isfinite(lower[i]) and np.isfinite(upper[i])):
            raise SceneError(f"{source}: robot.limits: position {names[i]!r} is unbounded; give its limits")
    weights = np.array([spec.weights.get(names[i], 1.0) for i in idx])
    space = ConfigSpace(tuple(names[i] for i in idx), lower[idx], upper[idx], weights, wrap[idx])
    return Coordinates(space, tuple(idx), q_full, revolute[idx])


def unbounded_positions(plant, robot) -> list[str]:
    """The robot's positions without finite limits that do not wrap: planning needs ``robot.limits`` for them."""
    names = plant.GetPositionNames(robot, add_model_instance_prefix=False, always_add_suffix=False)
    lower, upper = (plant.GetPositionsFromArray(robot, v) for v in (plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()))
    wrap = plant.GetPositionsFromArray(robot, _joint_layout(plant, robot)[0].astype(float)) > 0.5
    bounded = np.isfinite(lower) & np.isfinite(upper)
    return [n for n, w, b in zip(names, wrap, bounded) if not (w or b)]


def _joint_layout(plant, robot) -> tuple[np.ndarray, list[str]]:
    """Per plant position: whether it is a wrapping angle, and the name of its joint."""
    wrap = np.zeros(plant.num_positions(), bool)
    joint_of = [""] * plant.num_positions()
    for ji in plant.GetJointIndices(robot):
        joint = plant.get_joint(ji)
        for k in range(joint.num_positions()):
            joint_of[joint.position_start() + k] = joint.name()
        if isinstance(joint, PlanarJoint):
            wrap[joint.position_start() + 2] = True
        elif isinstance(joint, RevoluteJoint) and not np.isfinite(joint.position_upper_limits()[0]):
            wrap[joint.position_start()] = True
    return wrap, joint_of
