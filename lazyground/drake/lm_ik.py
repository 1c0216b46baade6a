"""Inverse kinematics by batched damped least squares (Levenberg-Marquardt) over a :class:`Chain`.

Many random starts are solved at once: every step is a few numpy operations on
(B, 6, n) arrays, so 16 starts cost about what one does. Each start has its own
damping, halved after a step that lowers its error and multiplied by 4 after
one that does not (the step is then not taken). Joint limits are enforced by
clipping (angles of continuous joints wrap instead). A start has converged when
its position error is below ``position_tolerance`` and its rotation error below
``orientation_tolerance``: tighter than the goal regions' slack, so solved poses
lie where they were sampled.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.drake.chain import Chain
from lazyground.geometry import wrap_angle


@dataclass(frozen=True)
class LMSettings:
    position_tolerance: float = 5e-4  # m
    orientation_tolerance: float = 2e-3  # rad
    max_iterations: int = 40
    rotation_weight: float = 0.5  # m per rad in the least-squares error
    initial_damping: float = 0.05
    max_step: float = 0.5  # rad (or m) per coordinate per iteration


def rotation_error(R_target: np.ndarray, R: np.ndarray) -> np.ndarray:
    """Rotation vectors (B, 3), in world, that turn each R (B, 3, 3) into R_target (3, 3)."""
    E = R_target[None] @ R.transpose(0, 2, 1)
    v = 0.5 * np.stack([E[:, 2, 1] - E[:, 1, 2], E[:, 0, 2] - E[:, 2, 0], E[:, 1, 0] - E[:, 0, 1]], axis=1)
    s = np.linalg.norm(v, axis=1)
    c = np.clip((np.trace(E, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arctan2(s, c)
    scale = np.where(s > 1e-12, angle / np.maximum(s, 1e-12), 1.0)
    return v * scale[:, None]


def solve_lm(
    chain: Chain,
    X_WT: np.ndarray,
    q0: np.ndarray,
    lower: np.ndarray,
    upper: np.ndarray,
    wrap: np.ndarray,
    settings: LMSettings = LMSettings(),
) -> tuple[np.ndarray, np.ndarray, int]:
    """Solve from the starts ``q0`` (B, n) over the chain's coordinates.

    Args:
        chain: the kinematic chain to the constrained frame.
        X_WT: the target pose (4, 4) of the chain's end frame.
        q0: starting configurations, one row per start.
        lower, upper: coordinate limits (n,); ``wrap`` marks angles that wrap.
        settings: tolerances and iteration limit.

    Returns:
        (q, converged, iterations): the final rows (B, n), a mask of the rows
        that reached the tolerances, and the iterations run. Iteration stops as
        soon as one row has converged.
    """
    s = settings
    q = np.array(q0, float, ndmin=2)
    B, n = q.shape
    w = np.array([s.rotation_weight] * 3 + [1.0] * 3)
    R_T, p_T = X_WT[:3, :3], X_WT[:3, 3]

    def residual(X):
        e = np.concatenate([rotation_error(R_T, X[:, :3, :3]), p_T - X[:, :3, 3]], axis=1)
        return e, np.linalg.norm(e[:, :3], axis=1), np.linalg.norm(e[:, 3:], axis=1)

    X, J = chain.forward(q, jacobian=True)
    e, rot, pos = residual(X)
    cost = np.einsum("bi,bi->b", e * w, e * w)
    damping = np.full(B, s.initial_damping)
    eye = np.eye(6)
    for it in range(1, s.max_iterations + 1):
        converged = (pos <= s.position_tolerance) & (rot <= s.orientation_tolerance)
        if converged.any():
            return q, converged, it - 1
        Jw = J * w[None, :, None]
        A = Jw @ Jw.transpose(0, 2, 1) + (damping**2)[:, None, None] * eye
        dq = np.einsum("bji,bj->bi", Jw, np.linalg.solve(A, (e * w)[..., None])[..., 0])
        dq = np.clip(dq, -s.max_step, s.max_step)
        q_new = q + dq
        q_new[:, wrap] = wrap_angle(q_new[:, wrap])
        q_new = np.where(wrap, q_new, np.clip(q_new, lower, upper))
        X_new, J_new = chain.forward(q_new, jacobian=True)
        e_new, rot_new, pos_new = residual(X_new)
        cost_new = np.einsum("bi,bi->b", e_new * w, e_new * w)
        better = cost_new < cost
        q[better], J[better], e[better] = q_new[better], J_new[better], e_new[better]
        rot[better], pos[better], cost[better] = rot_new[better], pos_new[better], cost_new[better]
        damping = np.where(better, damping * 0.5, damping * 4.0).clip(1e-6, 1e3)
    converged = (pos <= s.position_tolerance) & (rot <= s.orientation_tolerance)
    return q, converged, s.max_iterations
