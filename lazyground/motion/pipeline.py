"""After a solve: shorten the path, then time it (what ``api.plan`` runs by default)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lazyground.motion.shortcut import ShortcutResult, ShortcutSettings, ShortcutStatus, shortcut_path
from lazyground.motion.trajectory import Limits, MotionError, TimingSettings, Trajectory, time_path
from lazyground.planning.car import CarSpace
from lazyground.planning.stop import default_clock  # the split's clock (tests drive it)
from lazyground.planning.problem import PlanResult, ValidityChecker
from lazyground.settings import MotionSettings, RunSettings
from lazyground.planning.space import ConfigSpace


def shortcut_settings(settings: MotionSettings) -> ShortcutSettings:
    """The shortcut's settings from the run's motion settings (declared in lazyground.settings)."""
    return ShortcutSettings(enabled=settings.shortcut_iterations > 0, max_iterations=settings.shortcut_iterations,
                            time_budget=settings.shortcut_time)


def timing_settings(settings: MotionSettings) -> TimingSettings:
    return TimingSettings(speed=settings.speed, sample_rate=settings.sample_rate)


@dataclass(frozen=True)
class Motion:
    """The shortened path and its timed trajectory (None when timing is off or impossible)."""

    shortcut: ShortcutResult
    trajectory: Trajectory | None
    shortcut_s: float
    timing_s: float
    note: str = ""  # why there is no trajectory
    cusps: int | None = None  # a car's gear changes along the path (None: not a car; lazyground.motion.car_shortcut)

    @property
    def raw_path(self) -> np.ndarray:
        return self.shortcut.raw_path

    @property
    def raw_length(self) -> float:
        return self.shortcut.raw_length

    @property
    def direct_length(self) -> float:
        return self.shortcut.direct_length

    @property
    def time_s(self) -> float:
        return self.shortcut_s + self.timing_s


def make_motion(
    space: ConfigSpace,
    checker: ValidityChecker,
    result: PlanResult,
    settings: RunSettings,
    limits: Limits | None,
    rng: np.random.Generator,
    stops: tuple[int, ...] | None = None,
    car: CarSpace | None = None,
) -> Motion:
    """Shorten and time a solved result's path.

    Args:
        space: the planner's configuration space.
        checker: the planner's validity checker.
        result: a solved PlanResult (its goal's ``final`` marks a straight approach to keep).
        settings: the run's: the planner's (resolution, validation factor) and the motion's
            (shortcut_iterations, shortcut_time, speed, sample_rate).
        limits: velocity/acceleration limits; None: no trajectory.
        rng: the plan's generator (continues its stream, so the motion follows from the seed).
        stops: None to shorten the path; else it is timed as driven (a car's curves), not
            shortened, resting at these waypoints (its gear changes).
        car: the car space of a car's path (with ``stops``): timed along its curves as a car drives
            (:mod:`lazyground.motion.car_timing`).

    Returns:
        The Motion; its ``shortcut.path`` passed the fine re-check.
    """
    approach = result.goal is not None and result.goal.final is not None
    planner = settings.planner
    cut = shortcut_settings(settings.motion)
    short = shortcut_path(space, checker, result.path, planner.resolution, planner.validation_factor,
                          replace(cut, enabled=False) if stops is not None else cut, rng, keep_last_segment=approach)
    if limits is None:
        return Motion(short, None, short.time_s, 0.0, "no limits for timing")
    t0 = default_clock()
    fine = planner.resolution / planner.validation_factor
    for attempt in (short, _reverted(short)):
        rests = tuple(stops or ()) + ((len(attempt.path) - 2,) if approach else ())
        try:
            # The whole sampled curve is checked, not only the corners off the (fine-checked) path: the re-check
            # at the same resolution tests other points of those segments, and a path grazing an obstacle
            # between the two sets failed it (panda_tabletop, "pick up cup_shelf", seed 3).
            timing = timing_settings(settings.motion) if stops is not None else timing_settings(settings.motion).for_shortened()
            traj = time_path(space, checker, attempt.path, limits, fine, timing, stops=rests, car=car)
        except MotionError as exc:
            if attempt.path is attempt.raw_path:
                return Motion(short, None, short.time_s, default_clock() - t0, f"no trajectory: {exc}")
            continue  # a shortcut segment grazes an obstacle between its fine checks: time the raw path instead
        return Motion(attempt, traj, short.time_s, default_clock() - t0)
    raise AssertionError("unreachable")


def _reverted(short: ShortcutResult) -> ShortcutResult:
    return replace(short, status=ShortcutStatus.REVERTED, path=short.raw_path, length=short.raw_length)


def with_motion(result: PlanResult, motion: Motion) -> PlanResult:
    """The result with the shortened path as its path (the raw one stays in ``motion``)."""
    return replace(result, path=motion.shortcut.path, path_length=motion.shortcut.length)


def motion_for_world(world, result: PlanResult, settings: RunSettings,
                     rng: np.random.Generator, stops: tuple[int, ...] | None = None,
                     car: CarSpace | None = None) -> tuple[PlanResult, Motion | None]:
    """The API's hook: shorten and time a result planned in a DrakeWorld.

    Returns:
        (the result with the shortened path, its Motion); (result, None) when it is not solved.
        A robot without limits gets a Motion without trajectory and a note saying why.
    """
    if not result.solved or result.path is None:
        return result, None
    from lazyground.motion.limits import world_limits
    from lazyground.typed_yaml import SceneError

    try:
        limits, note = world_limits(world), ""
    except SceneError as exc:
        limits, note = None, f"no trajectory: {exc}"
    motion = make_motion(world.space, world, result, settings, limits, rng, stops, car)
    if note and not motion.note:
        motion = replace(motion, note=note)
    if stops is not None:  # timed as driven, not shortened: the path and its (driven) length stay the planner's
        return result, motion
    return with_motion(result, motion), motion
