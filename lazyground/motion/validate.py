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
    dense = np.vstack([space.discretize(a, b, resolution, skip_first=k > 0) for k, (a, b) in enumerate(zip(traj.q[:-1], traj.q[1:]))])
    free = checker.configs_free(space.interpolate(dense, dense, 0.0) if space.wrap.any() else dense)
    if from_first_free:
        free = free[int(np.argmax(free)):]
    if not np.all(free):
        problems.append(f"trajectory collides at resolution {resolution:g}")
    return problems
