"""Per-coordinate velocity and acceleration limits of a Drake world's planned coordinates.

Velocities come from the model (URDF ``<limit velocity=...>``) unless the robot's
``robot.yaml`` overrides them (``velocity_limits``: a car's planar joint has none in its
URDF); accelerations come from ``robot.yaml`` only (``acceleration_limits``, then
``default_acceleration``), as URDFs carry none. Keys are joint names or position names
(a planar joint's ``car_x``, ``car_y``, ``car_qz``).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np

from lazyground.robots.defaults import RobotDefaults, defaults_for_model
from lazyground.typed_yaml import SceneError


@dataclass(frozen=True)
class Limits:
    """Per-coordinate velocity and acceleration limits (positive, finite)."""

    velocity: np.ndarray
    acceleration: np.ndarray

    def __post_init__(self):
        for name in ("velocity", "acceleration"):
            v = np.asarray(getattr(self, name), float)
            if not (np.all(np.isfinite(v)) and np.all(v > 0)):
                raise ValueError(f"{name} limits must be positive and finite, got {v}")
            object.__setattr__(self, name, v)



def position_joints(plant, instance) -> dict[int, str]:
    """Plant position index -> the name of the joint it belongs to."""
    out = {}
    for ji in plant.GetJointIndices(instance):
        joint = plant.get_joint(ji)
        for k in range(joint.num_positions()):
            out[joint.position_start() + k] = joint.name()
    return out


_WORLD_LIMITS: "weakref.WeakKeyDictionary[object, Limits]" = weakref.WeakKeyDictionary()


def world_limits(world, defaults: RobotDefaults | None = None) -> Limits:
    """The limits of ``world``'s planned coordinates (see module docstring); with the default ``defaults``,
    read once per world (its model and robot.yaml are read when it is built: ~1 ms a request otherwise).

    Args:
        world: a DrakeWorld (``plant``, ``robot``, ``planned``, ``space``, ``scene``).
        defaults: the robot's defaults (default: the ``robot.yaml`` beside the scene's model).

    Raises:
        SceneError: a planned coordinate has no finite velocity or no acceleration limit.
    """
    if defaults is None:
        if world not in _WORLD_LIMITS:
            _WORLD_LIMITS[world] = _limits(world, defaults_for_model(world.scene.robot.model))
        return _WORLD_LIMITS[world]
    return _limits(world, defaults)


def _limits(world, defaults: RobotDefaults | None) -> Limits:
    plant = world.plant
    if plant.num_positions() != plant.num_velocities():
        raise SceneError(f"{world.scene.source}: robot.model: time parameterisation needs q̇ = v (no floating bodies)")
    joint_of = position_joints(plant, world.robot)
    v_model = plant.GetVelocityUpperLimits()
    velocity, acceleration = [], []
    where = defaults.source if defaults is not None else f"a robot.yaml beside {world.scene.robot.model}"
    for i, name in zip(world.planned, world.space.names):
        keys = (name, joint_of.get(i, name))
        v = _lookup(defaults.velocity_limits if defaults else {}, keys, v_model[i])
        a = _lookup(defaults.acceleration_limits if defaults else {}, keys, defaults.default_acceleration if defaults else None)
        if v is None or not np.isfinite(v) or v <= 0:
            raise SceneError(f"{where}: velocity_limits: no velocity limit for {name!r} (the model gives none)")
        if a is None:
            raise SceneError(f"{where}: acceleration_limits: no acceleration limit for {name!r} (nor default_acceleration)")
        velocity.append(v)
        acceleration.append(a)
    return Limits(np.array(velocity), np.array(acceleration))


def _lookup(table: dict[str, float], keys: tuple[str, ...], fallback):
    for key in keys:
        if key in table:
            return table[key]
    return fallback
