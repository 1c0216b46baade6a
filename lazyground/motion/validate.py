"""Re-checking a timed trajectory as a user of it would: ends, collisions along the curve, limits."""

from __future__ import annotations

import numpy as np

from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace

LIMIT_TOLERANCE = 0.01  # samples may exceed a limit by 1% (rounding of the uniform slow-down)


def trajectory_problems(
    traj,
    space: ConfigSpace,
    checker: ValidityChecker,
    start: np.ndarray,
    goal: np.ndarray,
    resolution: float,
    from_first_free: bool = False,
) -> list[str]:
    """What is wrong with a Trajectory (empty: nothing).

    Consecutive samples are joined and the joins checked every ``resolution`` (the curve, not
    only its samples); positions, velocities and accelerations against the trajectory's limits.

    Args:
        traj: a :class:`~lazyground.motion.trajectory.Trajectory`.
        space, checker: the world it must be free in.
        start, goal: where it must start and end (wrapping coordinates compared modulo 2 pi).
        resolution: the check's spacing (the planner's fine resolution).
        from_first_free: check only from the first free configuration on (a lift-off whose
            carried object starts on its support).
    """
    problems = []
    if not np.allclose(space.difference(traj.q[0], start), 0.0, atol=1e-6):
        problems.append("trajectory does not start at the start configuration")
    if not np.allclose(space.difference(traj.q[-1], goal), 0.0, atol=1e-6):
        problems.append("trajectory does not end at the goal configuration")
    if np.any(np.diff(traj.t) <= 0):
        problems.append("trajectory times do not increase")
    if not np.allclose(traj.qd[[0, -1]], 0.0, atol=1e-6):
        problems.append("trajectory does not start and end at rest")
    for name, values, limit in (("velocity", traj.qd, traj.limits.velocity), ("acceleration", traj.qdd, traj.limits.acceleration)):
        ratio = float(np.max(np.abs(values) / limit))
        if ratio > 1.0 + LIMIT_TOLERANCE:
            problems.append(f"trajectory exceeds a {name} limit {ratio:.3f}x")
    if first_colliding_join(space, checker, traj.q, resolution, from_first_free) is not None:
        problems.append(f"trajectory collides at resolution {resolution:g}")
    return problems


def first_colliding_join(space: ConfigSpace, checker: ValidityChecker, q: np.ndarray, resolution: float,
                         from_first_free: bool = False, along: bool = False) -> int | None:
    """The sample k where the motion through ``q`` first collides, checked every ``resolution``; None if free.

    The one check of sampled motions: :func:`trajectory_problems` and the timing itself
    (:func:`lazyground.motion.trajectory.time_path` checks its output with it, so what it
    returns passes this re-check by construction). ``along``: through :func:`sequence_free` (the
    timing's; the same answers, cheaper), else ``configs_free`` (the re-check's).
    """
    q = np.asarray(q, float)
    if len(q) < 2:
        return None
    dense, owner = _dense(space, q, resolution)
    dense = space.interpolate(dense, dense, 0.0) if space.wrap.any() else dense
    free = sequence_free(checker, dense) if along else checker.configs_free(dense)
    if from_first_free:
        free[: int(np.argmax(free))] = True
    bad = np.flatnonzero(~free)
    return None if not len(bad) else int(owner[bad[0]])


def sequence_free(checker: ValidityChecker, qs: np.ndarray) -> np.ndarray:
    """``checker.configs_free(qs)`` for configurations in sequence along a path, through the checker's
    ``configs_free_along`` when it has one (lazyground.drake: most proven from the ones before)."""
    along = getattr(checker, "configs_free_along", None)
    return along(qs) if along is not None else checker.configs_free(qs)


def _dense(space: ConfigSpace, q: np.ndarray, resolution: float) -> tuple[np.ndarray, np.ndarray]:
    """Configurations along the joins of q at most ``resolution`` apart, and the sample each follows.

    The points lie evenly along the polyline through all samples (its first and last included), at
    most ``resolution`` of arc length apart; a trajectory's samples are often less than ``resolution``
    apart (a robot speeding up or slowing down) or just over it, and discretizing join by join would
    check up to twice as many configurations for the same spacing.
    """
    e = space.embed(q)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(e, axis=0), axis=1))])
    t = np.linspace(0.0, s[-1], max(1, int(np.ceil(s[-1] / resolution))) + 1)
    k = np.clip(np.searchsorted(s, t, side="right") - 1, 0, len(q) - 2)
    span = s[k + 1] - s[k]
    frac = np.divide(t - s[k], span, out=np.zeros_like(t), where=span > 0)
    points = q[k] + np.clip(frac, 0.0, 1.0)[:, None] * space.difference(q[k], q[k + 1])
    points[-1] = q[-1]
    return points, k
