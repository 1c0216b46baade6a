"""After a solve, the post-processing a space chose: shorten, then time (OMPL's path simplifier, chosen once).

Every space names its post-processing (``ConfigSpace.post_processing``); this table maps the
name to a function ``(space, world, result, settings, rng) -> (result, Motion | None)``. Tasks
call :func:`post_process` and never ask which kind of space they planned in.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from lazyground.motion.car_shortcut import shorten_and_time_car
from lazyground.motion.pipeline import Motion, motion_for_world
from lazyground.planning.problem import PlanResult
from lazyground.planning.space import ConfigSpace
from lazyground.settings import RunSettings

PostProcessor = Callable[[ConfigSpace, object, PlanResult, RunSettings, np.random.Generator],
                         tuple[PlanResult, Motion | None]]


def _straight(space: ConfigSpace, world, result: PlanResult, settings: RunSettings,
              rng: np.random.Generator) -> tuple[PlanResult, Motion | None]:
    """Straight shortcuts, then a timed spline (lazyground.motion.pipeline)."""
    return motion_for_world(world, result, settings, rng)


POST_PROCESSORS: dict[str, PostProcessor] = {
    "straight": _straight,  # ConfigSpace: arms, the holonomic car
    "curves": shorten_and_time_car,  # CarSpace: Reeds-Shepp and Dubins cars
}


def post_process(space: ConfigSpace, world, result: PlanResult, settings: RunSettings,
                 rng: np.random.Generator) -> tuple[PlanResult, Motion | None]:
    """Shorten and time a result the way its space asks (a no-op Motion of None when it is not solved).

    Args:
        space: the space the result was planned in (its ``post_processing`` picks the processor).
        world: the DrakeWorld it was planned in (checker and limits).
        result: the planner's result.
        settings: the run's settings (the planner's resolution, the motion's budgets, speed, sample rate).
        rng: the plan's generator (continues its stream, so the motion follows from the seed).

    Raises:
        KeyError: the space names a post-processing that is not registered.
    """
    return POST_PROCESSORS[space.post_processing](space, world, result, settings, rng)
