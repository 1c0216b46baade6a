"""Which space a robot plans in for each kinematics: one registry, as the planners' and strategies'.

A kinematics is a value of :class:`lazyground.settings.Kinematics` (the ``kinematics`` setting) and a
factory here that makes its space from the robot's plain space (bounds, weights, wrapping angles),
its turning radius and the offset of its reference point. The space owns everything else
(interpolation, motion validation, the path it returns, its post-processing); a new kinematics is
one space module and one line below (docs/spaces.md).
"""

from __future__ import annotations

from typing import Callable

from lazyground.planning.car import car_space
from lazyground.planning.space import ConfigSpace
from lazyground.settings import Kinematics

SpaceFactory = Callable[[ConfigSpace, Kinematics, float, float], ConfigSpace]


def _holonomic(base: ConfigSpace, kinematics: Kinematics, radius: float, offset: float) -> ConfigSpace:
    return base  # straight lines in (x, y, heading): the paper's sliding car


SPACES: dict[Kinematics, SpaceFactory] = {
    Kinematics.HOLONOMIC: _holonomic,
    Kinematics.REEDS_SHEPP: car_space,
    Kinematics.DUBINS: car_space,
}


def make_space(base: ConfigSpace, kinematics: str | Kinematics, radius: float, offset: float = 0.0) -> ConfigSpace:
    """The space of ``kinematics`` over ``base`` (``base`` itself for a holonomic robot).

    Raises:
        ValueError: an unknown kinematics, or one without a registered space.
    """
    kinematics = Kinematics(kinematics)
    factory = SPACES.get(kinematics)
    if factory is None:
        raise ValueError(f"no space registered for kinematics {kinematics} (lazyground.planning.kinematics.SPACES)")
    return factory(base, kinematics, float(radius), float(offset))
