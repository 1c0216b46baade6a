"""The planning space of a car scene: its kinematics setting and the car's steering from robot.yaml."""

from __future__ import annotations

from pathlib import Path

from lazyground.planning.kinematics import make_space
from lazyground.planning.space import ConfigSpace
from lazyground.robots.defaults import defaults_for_model
from lazyground.scene.loader import resolve_model
from lazyground.settings import Kinematics
from lazyground.typed_yaml import SceneError


def planning_space(scene, base: ConfigSpace, kinematics: str) -> ConfigSpace:
    """``base`` for holonomic planning, else the car space of the scene's robot.

    The turning radius is the robot.yaml's ``kinematics`` (wheelbase / tan(max steering
    angle), at the rear axle centre); the axles are taken as centred on the model's body
    frame, so the rear axle sits wheelbase / 2 behind it.

    Raises:
        SceneError: car kinematics were asked for a robot whose robot.yaml has none.
    """
    if Kinematics(kinematics) is Kinematics.HOLONOMIC:
        return base
    model = resolve_model(scene.robot.model, Path(scene.source).parent if scene.source else None)
    car = defaults_for_model(model).kinematics if model is not None and defaults_for_model(model) else None
    if car is None:
        where = Path(model).parent / "robot.yaml" if model is not None else f"models/{scene.robot.model}/robot.yaml"
        raise SceneError(f"{scene.source or scene.name}: planner.kinematics: {kinematics} needs the robot's "
                         f"steering (kinematics: in {where}); this robot has none")
    return make_space(base, kinematics, car.min_turning_radius, offset=-0.5 * car.wheelbase)
