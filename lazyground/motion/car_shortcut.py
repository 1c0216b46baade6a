"""Shortening a car's path along its own curves (issue #17).

A car path comes out of the planner densely sampled along Reeds-Shepp (or Dubins) curves,
with many gear changes where the tree wandered. :mod:`lazyground.motion.shortcut` would join
two of its points by a straight line in (x, y, heading), which a car cannot drive; here a
sub-path between two of its samples is replaced by the shortest curve between them when that
curve is free at the planner's edge resolution, shorter, and has no more gear changes
(counting the joins with what comes before and after). The path stays a sequence of its own
samples (``keep``: indices into the dense input) joined by curves, so a replaced stretch is
always known and a curve that fails the fine re-check (``resolution / validation_factor``,
as every returned path) is put back as it was driven.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lazyground.geometry import wrap_angle
from lazyground.motion.pipeline import Motion, motion_for_world
from lazyground.motion.shortcut import ShortcutStatus
from lazyground.planning import curves
from lazyground.planning.car import DENSE_SPACING, CarSpace, drive_profile
from lazyground.planning.problem import PlanResult, ValidityChecker
from lazyground.planning.motion_validator import samples_free
from lazyground.planning.search import path_is_valid
from lazyground.planning.stop import StopCondition
from lazyground.settings import RunSettings

_SPARSE = 8  # the first pass of a candidate curve's collision check takes every 8th sample


@dataclass(frozen=True)
class CarShortcut:
    """A car path after shortening: dense samples, its driven length and gear changes, before and after."""

    path: np.ndarray
    raw_path: np.ndarray
    length: float
    raw_length: float
    cusps: int
    raw_cusps: int
    iterations: int
    accepted: int
    reverted: int  # accepted curves put back because they failed the fine re-check
    time_s: float


def driven_lengths(space: CarSpace, dense: np.ndarray) -> np.ndarray:
    """Metres driven by the reference point over each step of a dense car path.

    Every step of a dense path lies on one segment of a curve (its ends are samples): an arc
    of the turning radius where the heading changes, else a straight line.
    """
    ref = space.reference(dense)
    turn = np.abs(wrap_angle(np.diff(ref[:, 2])))
    chord = np.hypot(*np.diff(ref[:, :2], axis=0).T)
    return np.where(turn > 1e-9, space.radius * turn, chord)


def _flips(gears: list[float]) -> int:
    """Gear changes along a sequence of directions of travel (+1 / -1)."""
    return sum(a != b for a, b in zip(gears[:-1], gears[1:]))


def shorten_car_path(
    space: CarSpace,
    checker: ValidityChecker,
    dense: np.ndarray,
    resolution: float,
    validation_factor: float,
    max_iterations: int,
    stop: StopCondition,
    rng: np.random.Generator,
) -> CarShortcut:
    """Shortcut a dense car path by curves between its own samples (start and goal kept).

    Args:
        space: the car space the path was planned in.
        checker: the planner's validity checker.
        dense: (n, 3) samples along the planned curves (``PlanResult.path`` of a car).
        resolution: the planner's edge resolution; candidate curves are checked at it.
        validation_factor: new curves of the result are re-checked at ``resolution / validation_factor``.
        max_iterations: shortcut attempts (pairs of samples tried).
        stop: when to stop trying (its deadline: the shortcut's time budget); whichever of it and
            ``max_iterations`` comes first stops the attempts.
        rng: the only source of randomness (the plan's generator).

    Returns:
        A CarShortcut; every curve of its path that is not a piece of ``dense`` passed the fine re-check.
    """
    t0 = stop.now()
    dense = np.asarray(dense, float)
    steps = driven_lengths(space, dense)
    gears = drive_profile(space.reference(dense))
    # the current path: samples keep[k] and keep[k + 1] joined by a curve of length hop_len[k]
    # and directions of travel hop_gears[k] (a piece of the input path when they are neighbours)
    keep = list(range(len(dense)))
    hop_len = [float(v) for v in steps]
    hop_gears = [[g] if g else [] for g in gears.tolist()]
    iterations = accepted = 0
    while iterations < max_iterations and len(keep) > 2 and not stop.should_stop():
        iterations += 1
        i, j = sorted(rng.choice(len(keep), size=2, replace=False).tolist())
        if j - i < 2:
            continue
        word = space.word(dense[keep[i]], dense[keep[j]])
        new_len = curves.word_length(word)
        if new_len >= sum(hop_len[i:j]) - 1e-6:
            continue
        new_gears = [1.0 if s > 0.0 else -1.0 for _, s in word if abs(s) > 1e-12]
        before = next((g[-1] for g in reversed(hop_gears[:i]) if g), None)
        after = next((g[0] for g in hop_gears[j:] if g), None)
        ends = ([before] if before else [], [after] if after else [])
        old = ends[0] + [g for hop in hop_gears[i:j] for g in hop] + ends[1]
        if _flips(ends[0] + new_gears + ends[1]) > _flips(old):
            continue
        if not _curve_free(space, checker, dense[keep[i]], dense[keep[j]], resolution):
            continue
        keep[i + 1 : j], hop_len[i:j], hop_gears[i:j] = [], [new_len], [new_gears]
        accepted += 1
    keep, reverted = _fine_checked(space, checker, dense, keep, resolution / validation_factor)
    path = _densified(space, dense, keep)
    length = float(sum(steps[a:b].sum() if b == a + 1 else space.distance(dense[a], dense[b])
                       for a, b in zip(keep[:-1], keep[1:])))
    return CarShortcut(path, dense, length, float(steps.sum()), space.cusps(path), space.cusps(dense),
                       iterations, accepted, reverted, stop.now() - t0)


def _curve_free(space: CarSpace, checker: ValidityChecker, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
    """Whether the curve a -> b is free at ``resolution``: every 8th sample first, the rest if those are.

    Most candidate curves across a parking lot run through a parked car or a wall for metres:
    the sparse pass rejects them at an eighth of the checks.
    """
    qs = space.discretize(a, b, resolution, skip_first=True)
    sparse = np.zeros(len(qs), bool)
    sparse[::_SPARSE] = True
    return bool(np.all(samples_free(space, checker, qs[sparse])) and np.all(samples_free(space, checker, qs[~sparse])))


def _fine_checked(space: CarSpace, checker: ValidityChecker, dense: np.ndarray, keep: list[int],
                  fine: float) -> tuple[list[int], int]:
    """``keep`` with every new curve that fails the fine check replaced by the samples it skipped."""
    new = [k for k, (a, b) in enumerate(zip(keep[:-1], keep[1:])) if b > a + 1]
    waypoints = dense[keep]
    bad = []
    for k in new:  # one batch per curve: a failure must name its curve, not only the first one
        if path_is_valid(space, checker, waypoints, fine, [k]) >= 0:
            bad.append(k)
    out = list(keep)
    for k in reversed(bad):
        out[k + 1 : k + 1] = range(keep[k] + 1, keep[k + 1])
    return out, len(bad)


def _densified(space: CarSpace, dense: np.ndarray, keep: list[int]) -> np.ndarray:
    """The kept samples joined by the input's own samples, or by new curves sampled densely."""
    parts = [dense[:1]]
    for a, b in zip(keep[:-1], keep[1:]):
        parts.append(dense[b : b + 1] if b == a + 1 else space.discretize(dense[a], dense[b], DENSE_SPACING, skip_first=True))
    return np.vstack(parts)


def shorten_car_result(space: CarSpace, checker: ValidityChecker, result: PlanResult, settings: RunSettings,
                       rng: np.random.Generator) -> tuple[PlanResult, CarShortcut | None]:
    """The task's hook: a solved car result with its path shortened along curves.

    Args:
        space: the car space it was planned in.
        checker: the planner's validity checker.
        result: the planner's result (its path dense along the curves).
        settings: the run's (the planner's resolution and validation factor, the motion's shortcut budgets).
        rng: the plan's generator (continues its stream, so the shortcut follows from the seed).

    Returns:
        (the result with the shortened path, its driven length and gear changes, the CarShortcut);
        (result, None) when it is not solved or shortcutting is off.
    """
    motion, planner = settings.motion, settings.planner
    if not result.solved or result.path is None or motion.shortcut_iterations <= 0:
        return result, None
    cut = shorten_car_path(space, checker, result.path, planner.resolution, planner.validation_factor,
                           motion.shortcut_iterations, StopCondition.after(motion.shortcut_time), rng)
    return replace(result, path=cut.path, path_length=cut.length), cut


def with_car_shortcut(motion: Motion | None, cut: CarShortcut | None) -> Motion | None:
    """The motion of a shortened car path, recording the planner's path as its raw path.

    Both lengths are driven metres, as the result's ``path_length``; a straight line in (x, y, heading)
    is no lower bound of what a car drives, so there is no direct length.
    """
    if motion is None or cut is None:
        return motion
    status = ShortcutStatus.SHORTENED if cut.length < cut.raw_length else ShortcutStatus.UNCHANGED
    short = replace(motion.shortcut, status=status, raw_path=cut.raw_path, raw_length=cut.raw_length,
                    length=cut.length, direct_length=float("nan"), iterations=cut.iterations,
                    accepted=cut.accepted - cut.reverted, time_s=cut.time_s)
    return replace(motion, shortcut=short, shortcut_s=cut.time_s)


def shorten_and_time_car(space: CarSpace, world, result: PlanResult, settings: RunSettings,
                         rng: np.random.Generator) -> tuple[PlanResult, Motion | None]:
    """A car's post-processing (``CarSpace.post_processing``, lazyground.motion.post): shortened along its
    curves (#17), then timed as driven, resting at every gear change (a straight shortcut would leave the
    curves); the motion records the gear changes (``cusps``)."""
    result, cut = shorten_car_result(space, world, result, settings, rng)
    stops = space.cusp_indices(result.path) if result.solved else None
    result, motion = motion_for_world(world, result, settings, rng, stops=stops, car=space)
    motion = with_car_shortcut(motion, cut)
    return result, None if motion is None else replace(motion, cusps=space.cusps(result.path))
