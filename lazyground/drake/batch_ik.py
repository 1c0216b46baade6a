"""Many IK problems at once: damped least squares on the numpy chain (#19).

A goal-sampling round poses dozens of IK problems (every live region x its drawn
target x several random starts). One SNOPT solve costs ~1.4 ms from Python, most
of it building and entering the program; here all problems are rows of one
(B, n) array and every iteration costs one batched forward-kinematics + Jacobian
evaluation (:meth:`~lazyground.drake.chain.Chain.forward`) and one batched 6x6
solve, whatever B is. Levenberg-Marquardt damping is kept per problem: a step
that lowers a problem's error is taken and its damping halved, one that does not
is undone and its damping raised, so far-off problems take short safe steps and
near ones Gauss-Newton steps. Joint limits are kept by clipping (continuous
joints wrap), as a projected step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.drake.chain import Chain

ITERATIONS = 15  # per problem; converged from random starts on fetch_cans_1: 83 % by 10, 93 % by 15, 95 % by 30 (SNOPT 64 %)
DAMPING = 0.05  # initial damping (m or rad), per problem
MIN_DAMPING, MAX_DAMPING = 1e-6, 1e3
ROTATION_WEIGHT = 0.3  # m per rad: how a rotation error weighs against a position error in the step


@dataclass(frozen=True)
class BatchIKProblem:
    """What does not change between the rows of a batch: the chain and the coordinates it may move.

    ``free`` marks the chain's joints IK may move (the planned ones); the others
    stay where the starting rows put them. ``lower``/``upper``/``wrap`` are per
    chain joint (wrap: a continuous angle, kept in [lower, upper) by wrapping).
    """

    chain: Chain
    free: np.ndarray  # (n,) bool
    lower: np.ndarray  # (n,)
    upper: np.ndarray  # (n,)
    wrap: np.ndarray  # (n,) bool

    def limit(self, q: np.ndarray) -> np.ndarray:
        """Rows ``q`` (B, n) brought within the limits: clipped, continuous joints wrapped."""
        out = np.clip(q, self.lower, self.upper)
        if self.wrap.any():
            span = self.upper - self.lower
            out[:, self.wrap] = self.lower[self.wrap] + np.mod(q[:, self.wrap] - self.lower[self.wrap], span[self.wrap])
        return out


def pose_errors(X: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World-frame errors of poses ``X`` (B, 4, 4) from targets ``T`` (B, 4, 4).

    Returns:
        (rotation vectors (B, 3) taking X's orientation to T's, position errors (B, 3)
        T - X, rotation angles (B,) in rad).
    """
    R = T[:, :3, :3] @ X[:, :3, :3].transpose(0, 2, 1)  # R_T R_X^T, in world
    cos = np.clip((np.trace(R, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arccos(cos)
    s = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)  # sin(angle) axis
    sin = np.sin(angle)
    ratio = np.where(sin > 1e-9, angle / np.maximum(sin, 1e-9), 1.0)
    w = s * ratio[:, None]
    near_pi = (cos < -0.999) & (np.linalg.norm(s, axis=1) < 1e-3)
    if near_pi.any():  # sin(angle) ~ 0 hides the axis: R + I has the axis (times 1 + cos) in every column
        M = R[near_pi] + np.eye(3)
        col = np.argmax(np.linalg.norm(M, axis=1), axis=1)
        axis = M[np.arange(len(M)), :, col]
        w[near_pi] = np.pi * axis / np.linalg.norm(axis, axis=1, keepdims=True)
    return w, T[:, :3, 3] - X[:, :3, 3], angle


def solve_batch(problem: BatchIKProblem, q0: np.ndarray, targets: np.ndarray, position_tolerance: float,
                orientation_tolerance: float, iterations: int = ITERATIONS) -> tuple[np.ndarray, np.ndarray]:
    """Damped least squares from B starts ``q0`` (B, n) towards B target poses ``targets`` (B, 4, 4).

    A problem stops once its frame is within ``position_tolerance`` (m, distance)
    and ``orientation_tolerance`` (rad) of its target, inside the region's box and
    cone; callers judge answers by forward kinematics again (the same chain, exact
    to 1e-12 against Drake).

    Args:
        problem: the chain and its limits.
        q0: starting chain configurations, within the limits.
        targets: world target poses of the chain's end frame.
        position_tolerance, orientation_tolerance: when a problem is done.
        iterations: forward-kinematics evaluations per problem at most.

    Returns:
        (answers (B, n), converged (B,) bool).
    """
    chain = problem.chain
    q = problem.limit(np.array(q0, float))
    B = len(q)
    weight = np.array([ROTATION_WEIGHT] * 3 + [1.0] * 3)
    X, J = chain.forward(q, jacobian=True)
    J = J * problem.free  # held joints do not move
    w, dp, angle = pose_errors(X, targets)
    e = np.concatenate([w, dp], axis=1) * weight
    cost = np.einsum("ij,ij->i", e, e)
    done = (np.linalg.norm(dp, axis=1) <= position_tolerance) & (angle <= orientation_tolerance)
    damping = np.full(B, DAMPING)
    for _ in range(iterations):
        live = np.flatnonzero(~done)
        if not len(live):
            break
        Jw = J[live] * weight[None, :, None]
        step = _step(Jw, e[live], damping[live])
        # A joint at a limit that the step pushes further out is held: the step is solved again
        # without it, so the other joints make up for it (clipping alone would stall there).
        blocked = ((q[live] <= problem.lower) & (step < 0)) | ((q[live] >= problem.upper) & (step > 0))
        blocked &= ~problem.wrap
        again = np.flatnonzero(blocked.any(axis=1))
        if len(again):
            step[again] = _step(Jw[again] * ~blocked[again][:, None, :], e[live][again], damping[live][again])
        q_try = problem.limit(q[live] + step)
        X_t, J_t = chain.forward(q_try, jacobian=True)
        w_t, dp_t, angle_t = pose_errors(X_t, targets[live])
        e_t = np.concatenate([w_t, dp_t], axis=1) * weight
        cost_t = np.einsum("ij,ij->i", e_t, e_t)
        better = cost_t < cost[live]
        take = live[better]
        q[take], J[take], e[take], cost[take] = q_try[better], J_t[better] * problem.free, e_t[better], cost_t[better]
        done[take] = (np.linalg.norm(dp_t[better], axis=1) <= position_tolerance) & (angle_t[better] <= orientation_tolerance)
        damping[take] = np.maximum(damping[take] * 0.5, MIN_DAMPING)
        worse = live[~better]
        damping[worse] = np.minimum(damping[worse] * 4.0, MAX_DAMPING)
    return q, done


def _step(Jw: np.ndarray, e: np.ndarray, damping: np.ndarray) -> np.ndarray:
    """Damped least-squares steps J^T (J J^T + d^2 I)^-1 e, row by row."""
    A = Jw @ Jw.transpose(0, 2, 1) + (damping ** 2)[:, None, None] * np.eye(6)
    return (Jw.transpose(0, 2, 1) @ np.linalg.solve(A, e[:, :, None]))[:, :, 0]
