"""TOPP-RA (Pham and Pham, "A new approach to time-optimal path parameterization based on reachability
analysis", IEEE T-RO 2018) under per-coordinate velocity and acceleration limits, in numpy.

Along a path q(s), with x = s'^2 and u = s'' on each grid interval (x_{i+1} = x_i + 2 delta_i u_i), the
limits are linear in (x, u): |q'_j| sqrt(x) <= v_j and |q'_j u + q''_j x| <= a_j. A backward pass finds
at every grid point the interval [K0_i, K1_i] of x from which the end can still be reached at rest; a
forward pass then takes the largest admissible u at every point. Every step is a linear program in the
two variables (x, u): here u is eliminated exactly (Fourier-Motzkin: every pair of an upper and a lower
bound on u gives a bound on x), where Drake's ``Toppra`` hands two such programs per grid point to a
general solver (~0.12 ms per grid point, the bulk of timing a Fetch path). The discretisation is Drake's
default (interpolation: the acceleration limits of grid point i + 1 also hold for (x_i, u_i)), its bound
x <= 1e16 and its s(t): piecewise quadratic, with the interval times from the mean of the end speeds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

X_MAX = 1e16  # Drake's bound on s'^2, so that a path with zero-speed spans keeps bounded sets
TOLERANCE = 1e-9  # relative: an empty interval narrower than this is rounding (an LP solver's tolerance)


@dataclass(frozen=True)
class PathTiming:
    """s(t): on [t[i], t[i + 1]], s = s[i] + sd[i] h + sdd[i] h^2 / 2 with h = t - t[i]."""

    t: np.ndarray  # (N + 1,)
    s: np.ndarray  # (N + 1,) the grid
    sd: np.ndarray  # (N + 1,)
    sdd: np.ndarray  # (N,)

    def end_time(self) -> float:
        return float(self.t[-1])

    def evaluate(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, s', s'' at times tau (each in the interval that starts at or before it)."""
        k = np.clip(np.searchsorted(self.t, tau, side="right") - 1, 0, len(self.sdd) - 1)
        h = tau - self.t[k]
        return self.s[k] + h * (self.sd[k] + 0.5 * h * self.sdd[k]), self.sd[k] + h * self.sdd[k], self.sdd[k]


def toppra(d1: np.ndarray, d2: np.ndarray, grid: np.ndarray, velocity: np.ndarray,
           acceleration: np.ndarray) -> PathTiming | None:
    """The time-optimal s(t) from rest to rest along the grid, or None when a step has no solution.

    Args:
        d1, d2: (N + 1, dim) q'(s) and q''(s) at the grid points.
        grid: (N + 1,) increasing path parameters.
        velocity, acceleration: (dim,) the limits.
    """
    delta = np.diff(grid)
    n = len(delta)
    alpha, beta, gamma = _rows(d1, d2, delta, acceleration)
    up, lo = beta > 0, beta < 0
    # x alone: the velocity limits, Drake's bound, the rows without u; then every pair of an upper and a lower
    # bound on u (Fourier-Motzkin)
    with np.errstate(divide="ignore"):
        x_hi = np.minimum(X_MAX, np.min((velocity / np.abs(d1[:n])) ** 2, axis=1))
    x_lo, hi = _bounds(alpha, gamma, beta == 0)
    x_hi = np.minimum(x_hi, hi)
    coef = beta[:, :, None] * alpha[:, None, :] - beta[:, None, :] * alpha[:, :, None]
    rhs = beta[:, :, None] * gamma[None, None, :] - beta[:, None, :] * gamma[None, :, None]
    lo_pairs, hi = _bounds(coef.reshape(n, -1), rhs.reshape(n, -1), (up[:, :, None] & lo[:, None, :]).reshape(n, -1))
    x_hi, x_lo = np.minimum(x_hi, hi), np.maximum(np.maximum(x_lo, lo_pairs), 0.0)
    # with the next point's interval [K0, K1]: x + 2 delta u <= K1 pairs with the lower rows, x + 2 delta u >= K0
    # with the upper ones, each giving x against (2 delta gamma - beta K) / (2 delta alpha - beta)
    two = 2.0 * delta
    c = two[:, None] * alpha - beta
    with np.errstate(divide="ignore", invalid="ignore"):
        base, slope = two[:, None] * gamma / c, -beta / c
    weights = np.stack([np.where(lo, slope, 0.0), np.where(up, slope, 0.0)], axis=2)  # on (K1, K0)
    bounding = (lo | up) & (c != 0)
    base_hi, base_lo = np.where(bounding & (c > 0), base, np.inf), np.where(bounding & (c < 0), base, -np.inf)
    w_hi, w_lo = np.where((c > 0)[:, :, None], weights, 0.0), np.where((c < 0)[:, :, None], weights, 0.0)
    K = np.zeros((n + 1, 2))  # (K1, K0); the end at rest
    for i in range(n - 1, -1, -1):
        hi_i = min(x_hi[i], float((base_hi[i] + w_hi[i] @ K[i + 1]).min()))
        lo_i = max(x_lo[i], float((base_lo[i] + w_lo[i] @ K[i + 1]).max()))
        if not lo_i <= hi_i + TOLERANCE * max(1.0, abs(hi_i)):
            return None
        K[i] = hi_i, max(min(lo_i, hi_i), 0.0)
    if K[0, 1] > 1e-8:  # Drake's test that the start at rest is controllable
        return None
    # forward: the largest u at every point, u <= (gamma - alpha x) / beta on the upper rows, >= on the lower
    with np.errstate(divide="ignore", invalid="ignore"):
        g, h = gamma / beta, alpha / beta
    g_hi, h_hi = np.where(up, g, np.inf), np.where(up, h, 0.0)
    g_lo, h_lo = np.where(lo, g, -np.inf), np.where(lo, h, 0.0)
    x = np.zeros(n + 1)
    u = np.zeros(n)
    for i in range(n):
        u_hi = min(float((g_hi[i] - h_hi[i] * x[i]).min()), (K[i + 1, 0] - x[i]) / two[i])
        u_lo = max(float((g_lo[i] - h_lo[i] * x[i]).max()), (K[i + 1, 1] - x[i]) / two[i])
        if not u_lo <= u_hi + TOLERANCE * max(1.0, abs(u_hi)):
            return None
        u[i] = u_hi
        x[i + 1] = min(max(x[i] + two[i] * u_hi, K[i + 1, 1]), K[i + 1, 0])
    sd = np.sqrt(x)
    mean = 0.5 * (sd[1:] + sd[:-1])
    dt = np.divide(delta, mean, out=np.full(n, np.inf), where=mean > 0)
    return PathTiming(np.concatenate([[grid[0]], grid[0] + np.cumsum(dt)]), grid, sd, u)


def _rows(d1: np.ndarray, d2: np.ndarray, delta: np.ndarray, acceleration: np.ndarray):
    """The acceleration limits at grid points 0 .. N-1 as rows alpha x + beta u <= gamma: the point's own, then
    grid point i + 1's for (x_i, u_i) with x_{i+1} = x_i + 2 delta_i u_i (the last point repeats its own), each
    as <= a and as >= -a. Returns alpha, beta (N, 4 dim) and gamma (4 dim,)."""
    n = len(delta)
    nxt_d1, nxt_d2 = np.vstack([d1[1:n], d1[n - 1 : n]]), np.vstack([d2[1:n], d2[n - 1 : n]])
    nxt_d1 = nxt_d1 + np.append(2.0 * delta[: n - 1], 0.0)[:, None] * nxt_d2
    alpha, beta = np.hstack([d2[:n], nxt_d2]), np.hstack([d1[:n], nxt_d1])
    return np.hstack([alpha, -alpha]), np.hstack([beta, -beta]), np.tile(acceleration, 4)


def _bounds(coef: np.ndarray, rhs: np.ndarray, keep: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per row of the arrays, (largest lower, smallest upper) bound on x from coef x <= rhs where ``keep``;
    0 <= rhs < 0 makes the upper bound -inf."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = rhs / coef
    upper = np.min(np.where(keep & (coef > 0), ratio, np.inf), axis=-1)
    lower = np.max(np.where(keep & (coef < 0), ratio, -np.inf), axis=-1)
    broken = np.any(keep & (coef == 0) & (rhs < 0), axis=-1)
    return lower, np.where(broken, -np.inf, upper)
