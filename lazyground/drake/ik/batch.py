"""Many IK problems at once: damped least squares on the chain (#19).

A goal-sampling round poses dozens of IK problems (every live region x its drawn
target x several random starts). One SNOPT solve costs ~1.4 ms from Python, most
of it building and entering the program; here all problems are rows of one
(B, n) array solved in one compiled call (:mod:`~lazyground.drake.ik.kernels`,
~10 µs a row on Fetch), each iteration one forward-kinematics + Jacobian evaluation
of the chain and one 6x6 solve. Levenberg-Marquardt damping is kept per problem: a step
that lowers a problem's error is taken and its damping halved, one that does not
is undone and its damping raised, so far-off problems take short safe steps and
near ones Gauss-Newton steps. Joint limits are kept by clipping (continuous
joints wrap), as a projected step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.drake.chain import Chain
from lazyground.drake.ik import kernels

ITERATIONS = 15  # per problem; converged from random starts on fetch_cans_1: 83 % by 10, 93 % by 15, 95 % by 30 (SNOPT 64 %)
DAMPING = 0.05  # initial damping (m or rad), per problem
MIN_DAMPING, MAX_DAMPING = 1e-6, 1e3
SETTLE = 0.05  # a problem is done this fraction of its tolerance outside it (judged later with SOLVER_SLACK 0.1)
ROTATION_WEIGHT = 0.3  # m per rad: how a rotation error weighs against a position error in the step
WEIGHT = np.array([ROTATION_WEIGHT] * 3 + [1.0] * 3)  # per error row (rotation; position)


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
    wrap: np.ndarray  # (n,) bool (the solver keeps rows within the limits: kernels.limit_row)


def pose_errors(X: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World-frame errors of poses ``X`` (B, 4, 4) from targets ``T`` (B, 4, 4).

    Returns:
        (rotation vectors (B, 3) taking X's orientation to T's, position errors (B, 3)
        T - X, rotation angles (B,) in rad).
    """
    R = T[:, :3, :3] @ X[:, :3, :3].transpose(0, 2, 1)  # R_T R_X^T, in world
    cos = np.clip((R[:, 0, 0] + R[:, 1, 1] + R[:, 2, 2] - 1.0) / 2.0, -1.0, 1.0)  # (np.trace: a slow reduction)
    angle = np.arccos(cos)
    s = 0.5 * np.stack([R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], axis=1)  # sin(angle) axis
    sin = np.sin(angle)
    ratio = np.where(sin > 1e-9, angle / np.maximum(sin, 1e-9), 1.0)
    w = s * ratio[:, None]
    near_pi = cos < -0.999
    if near_pi.any():
        near_pi &= np.linalg.norm(s, axis=1) < 1e-3
    if near_pi.any():  # sin(angle) ~ 0 hides the axis: R + I has the axis (times 1 + cos) in every column
        M = R[near_pi] + np.eye(3)
        col = np.argmax(np.linalg.norm(M, axis=1), axis=1)
        axis = M[np.arange(len(M)), :, col]
        w[near_pi] = np.pi * axis / np.linalg.norm(axis, axis=1, keepdims=True)
    return w, T[:, :3, 3] - X[:, :3, 3], angle


def solve_batch(problem: BatchIKProblem, q0: np.ndarray, targets: np.ndarray, position_tolerance: float,
                orientation_tolerance: float, iterations: int = ITERATIONS,
                accepted: tuple[float, float] = (0.0, 0.0)) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Damped least squares from B starts ``q0`` (B, n) towards B target poses ``targets`` (B, 4, 4).

    The error driven to zero is how far the frame lies *outside* the tolerance: the
    world-axis box +-``position_tolerance`` around the target point and the cone of
    ``orientation_tolerance`` around its orientation, as SNOPT's constraints in
    :meth:`~lazyground.drake.ik.IKGoalSource.solve`. A problem stops on the boundary
    it came to (within SETTLE of it), not at the target: restarts from different
    starts then end at different points of the tolerance, as SNOPT's do. Where a few
    millimetres decide a collision (a gripper under a shelf board) that is the room
    the restarts need: driven to the exact target, 3 restarts of a top grasp in a
    shelf gave near-identical gripper poses, and 0.6 % of the answers were free against
    SNOPT's 5 % (fetch_cans_2, Can2/top). Callers judge answers by forward kinematics
    again (the same chain, exact to 1e-12 against Drake).

    Args:
        problem: the chain and its limits.
        q0: starting chain configurations, within the limits.
        targets: world target poses of the chain's end frame.
        position_tolerance, orientation_tolerance: the tolerance box's half-width (m) and cone's angle (rad).
        iterations: forward-kinematics evaluations per problem at most.
        accepted: the (position, angle) error an answer may have and still meet its target
            (:func:`lazyground.tolerance.accepted_error`).

    Returns:
        (answers (B, n), converged (B,) bool, met (B,) bool: the answer's pose within ``accepted``).

    Compiled row by row (:mod:`~lazyground.drake.ik.kernels`): the same steps as the numpy
    batch it replaced, answers equal to ~1e-9 rad (fetch_cans_1, 800 random rows), ~8x less CPU.
    """
    chain = problem.chain
    q0 = np.ascontiguousarray(q0, float).reshape(-1, chain.n)
    targets = np.ascontiguousarray(targets, float).reshape(-1, 4, 4)
    B = len(q0)
    q, done, met = np.empty((B, chain.n)), np.empty(B, np.bool_), np.empty(B, np.bool_)
    kernels.solve_rows(q0, targets, chain.X_before, chain.X_after, chain.kinds, problem.free, problem.lower, problem.upper,
                          problem.wrap, float(position_tolerance), float(orientation_tolerance), int(iterations), DAMPING,
                          MIN_DAMPING, MAX_DAMPING, SETTLE, WEIGHT, float(accepted[0]), float(accepted[1]), q, done, met)
    return q, done, met
