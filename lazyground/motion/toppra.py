"""TOPP-RA for per-joint velocity and acceleration limits, in numpy (no Drake).

Pham and Pham, "A new approach to time-optimal path parameterization based on reachability
analysis", IEEE T-RO 2018. Along a path q(s) on a grid s_0 < ... < s_N, the state is x = ṡ² and
the control u = s̈, constant between grid points (x_{i+1} = x_i + 2 Δ_i u_i). The limits are
linear in (u, x): |q'_j u + q''_j x| <= a_j, imposed at s_i and, through x_{i+1}, at s_{i+1}
(Drake's ``ToppraDiscretization.kInterpolation``, its default), and x <= v_j² / q'_j² at s_i.
A backward pass finds the largest x_i from which the path can still stop at its end (the
controllable sets [0, c_i]: x = 0, u = 0 is always admissible, so each set is an interval
from 0); a forward pass from rest then takes the largest admissible u_i that stays inside the
next set. With only joint limits each pass step is a two-variable LP whose feasible x is an
interval: its upper end is the least of the bounds that pairs of an upper and a lower bound
on u give, all pairs at once. Drake's ``Toppra`` solved a generic LP per grid point (~0.2 ms
each, ~7 ms per Fetch curve); this takes ~1 ms per curve, for the same timing (durations
within 0.1 % on the Fetch scenes' curves, tests/unit/test_toppra.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PathTiming:
    """s(t) through the grid: at time t[i] the path is at s[i] with speed sd[i]; s̈ = sdd[i] until t[i + 1]."""

    t: np.ndarray  # (N + 1,)
    s: np.ndarray  # (N + 1,)
    sd: np.ndarray  # (N + 1,)
    sdd: np.ndarray  # (N,)

    def end_time(self) -> float:
        return float(self.t[-1])

    def evaluate(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, ṡ and s̈ at times ``tau`` (clipped to [0, end_time])."""
        tau = np.clip(np.asarray(tau, float), 0.0, self.end_time())
        i = np.clip(np.searchsorted(self.t, tau, side="right") - 1, 0, len(self.sdd) - 1)
        dt = tau - self.t[i]
        u = self.sdd[i]
        return self.s[i] + self.sd[i] * dt + 0.5 * u * dt * dt, self.sd[i] + u * dt, u


def toppra(grid: np.ndarray, dq: np.ndarray, ddq: np.ndarray, v_max: np.ndarray, a_max: np.ndarray) -> PathTiming | None:
    """The time-optimal rest-to-rest timing of a path on ``grid`` (TOPP-RA, see the module docstring).

    Args:
        grid: (N + 1,) increasing path parameters, its ends the path's.
        dq, ddq: (N + 1, dim) q'(s) and q''(s) at the grid points.
        v_max, a_max: (dim,) positive velocity and acceleration limits.

    Returns:
        The PathTiming; None when the path cannot be traversed (a speed of zero inside it: the grid is too
        coarse for the curve, or the curve stops).
    """
    grid = np.asarray(grid, float)
    n = len(grid) - 1
    delta = np.diff(grid)
    with np.errstate(divide="ignore"):
        x_vel = np.min(np.where(dq != 0.0, (v_max / np.where(dq != 0.0, np.abs(dq), 1.0)) ** 2, np.inf), axis=1)
    # per interval i the rows |alpha u + beta x| <= a_max: the limits at s_i, and at s_{i+1} through
    # x_{i+1} = x + 2 delta u. Each bounds u from above, u <= P + R x, and from below, u >= p + R x
    # (p = -P); a row with alpha = 0 bounds only x, as the velocity does
    alpha = np.concatenate([dq[:-1], dq[1:] + 2.0 * delta[:, None] * ddq[1:]], axis=1)  # (N, 2 dim)
    beta = np.concatenate([ddq[:-1], ddq[1:]], axis=1)
    gamma = np.concatenate([a_max, a_max])
    moving = alpha != 0.0
    safe = np.where(moving, alpha, 1.0)
    P = np.where(moving, gamma / np.abs(safe), np.inf)
    R = np.where(moving, -beta / safe, 0.0)
    p, r = -P, R
    with np.errstate(divide="ignore"):
        x_flat = np.min(np.where(moving, np.inf, gamma / np.abs(beta)), axis=1)
    # the staying-within-the-next-set rows: u <= (c_{i+1} - x) / 2 delta, u >= -x / 2 delta
    k = 1.0 / (2.0 * delta)
    # x bounds of the pairs that do not involve c_{i+1}: (lower row, upper row), and (u >= -x k, upper row)
    static = np.minimum(x_vel[:-1], x_flat)
    static = np.minimum(static, _pair_bound(p[:, :, None], r[:, :, None], P[:, None, :], R[:, None, :]))
    static = np.minimum(static, _pair_bound(0.0, -k[:, None], P, R))
    # (lower row, u <= (c - x) k): x <= (c k - p) / (r + k) where r + k > 0, i.e. x <= A c + B
    rise = r + k[:, None]
    ok = moving & (rise > 0.0)
    A = np.where(ok, k[:, None] / np.where(ok, rise, 1.0), 0.0)  # other rows: 0 c + inf
    B = np.where(ok, -p / np.where(ok, rise, 1.0), np.inf)
    c = np.empty(n + 1)
    c[n] = 0.0
    for i in range(n - 1, -1, -1):
        c[i] = max(min(static[i], float(np.min(A[i] * c[i + 1] + B[i]))), 0.0)
    x = np.zeros(n + 1)
    u = np.zeros(n)
    for i in range(n):
        u_hi = min(float(np.min(P[i] + R[i] * x[i])), (c[i + 1] - x[i]) * k[i])
        x[i + 1] = min(max(x[i] + 2.0 * delta[i] * u_hi, 0.0), c[i + 1])
        u[i] = (x[i + 1] - x[i]) * k[i]
    sd = np.sqrt(x)
    speed = sd[:-1] + sd[1:]
    if np.any(speed <= 0.0):
        return None
    t = np.concatenate([[0.0], np.cumsum(2.0 * delta / speed)])
    return PathTiming(t, grid, sd, u)


def _pair_bound(p, r, P, R) -> np.ndarray:
    """Per interval, the least upper bound on x of the pairs u >= p + r x, u <= P + R x (broadcast over the
    last axes): p + r x <= P + R x holds up to x = (P - p) / (r - R) where r > R (at x = 0 it holds: p <= 0 <= P)."""
    slope = r - R
    with np.errstate(divide="ignore", invalid="ignore"):
        bound = np.where(slope > 0.0, (P - p) / np.where(slope > 0.0, slope, 1.0), np.inf)
    return bound.reshape(len(bound), -1).min(axis=1)
