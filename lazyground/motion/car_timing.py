"""Timing a car's path as driven: the fastest speed along each gear segment's curve.

Each gear segment (the car rests at every gear change) becomes curves of continuous
curvature (:mod:`lazyground.motion.car_drive`), each timed along the rear axle's arc length
s by the classic time-optimal profile: with x = (ds/dt)^2 and u = d2s/dt2, every
coordinate's velocity q' ds/dt and acceleration q'' x + q' u must stay within its limits; a
backward pass from rest at the end gives the fastest speed from which the car can still
brake, a forward pass from rest at the start accelerates as hard as allowed under it (u
constant between grid nodes, both ends of each step within the limits). Sampled output that
still exceeds a limit between the nodes slows the motion uniformly, and a gear segment whose
sampled motion collides is redone with a smaller averaging window, at last on its exact
curves (:func:`lazyground.motion.trajectory.assemble`).
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass

import numpy as np

from lazyground.motion.car_drive import Drive, drives
from lazyground.motion.limits import Limits
from lazyground.planning.car import CarSpace

WINDOWS = (2.0, 1.0, 0.5, 0.0)  # m of curvature averaging, tried in order per gear segment (0: exact curves)
_EPS = 1e-12


def car_piece_timer(car: CarSpace, pieces: list[np.ndarray], limits: Limits):
    """(time_piece, levels) for :func:`lazyground.motion.trajectory.assemble`: gear segment k driven with
    averaging window ``WINDOWS[level]`` and timed under the (scaled) limits."""

    def time_piece(k: int, level: int):
        curves = drives(car, pieces[k], WINDOWS[level])
        used = Counter(d.window for d in curves) or Counter([0.0])
        # per gear segment, how its curves were driven: curvature averaged over w metres, or the exact curves
        label = ", ".join((f"curvature averaged over {w:g} m" if w > 0 else "exact curves") + (f" x{n}" if n > 1 else "")
                          for w, n in sorted(used.items(), reverse=True))
        return [time_drive(d, limits) for d in curves], label

    return time_piece, len(WINDOWS)


@dataclass(frozen=True)
class TimedDrive:
    """A Drive timed from rest to rest: speed squared ``x`` at its nodes, constant d2s/dt2 between them,
    played ``stretch`` times slower."""

    drive: Drive
    x: np.ndarray
    t: np.ndarray  # time at the nodes
    stretch: float = 1.0

    @property
    def duration(self) -> float:
        return float(self.t[-1]) * self.stretch

    def evaluate(self, t: np.ndarray):
        """q, qd, qdd at times t in [0, duration]."""
        tau = np.clip(np.asarray(t, float) / self.stretch, 0.0, self.t[-1])
        k = np.clip(np.searchsorted(self.t, tau, side="right") - 1, 0, len(self.t) - 2)
        s0 = self.drive.s
        u = (self.x[k + 1] - self.x[k]) / (2.0 * (s0[k + 1] - s0[k]))
        d = tau - self.t[k]
        v0 = np.sqrt(self.x[k])
        sd = np.maximum(v0 + u * d, 0.0)
        s = np.minimum(s0[k] + v0 * d + 0.5 * u * d**2, s0[k + 1])
        q, d1, d2 = self.drive.derivatives(s)
        sd, u = sd / self.stretch, u / self.stretch**2
        return q, d1 * sd[:, None], d2 * (sd**2)[:, None] + d1 * u[:, None]


def time_drive(drive: Drive, limits: Limits) -> TimedDrive:
    """The fastest rest-to-rest timing of ``drive`` under per-coordinate limits (see the module docstring)."""
    s = drive.s
    _, d1, right = drive.derivatives(s, right=True)
    _, _, left = drive.derivatives(s, right=False)
    cap = np.minimum(_speed_cap(d1, right, limits), _speed_cap(d1, left, limits))
    n = len(s) - 1
    h = np.diff(s)
    v, a = limits.velocity.tolist(), limits.acceleration.tolist()
    # per step k: dq/ds at both ends, d2q/ds2 at both ends with the step's own curvature slope
    p0, p1 = d1[:-1].tolist(), d1[1:].tolist()
    c0, c1 = right[:-1].tolist(), left[1:].tolist()
    cap_l, h_l = cap.tolist(), h.tolist()
    back = [0.0] * (n + 1)
    for k in range(n - 1, -1, -1):  # the fastest x_k from which x_{k+1} <= back[k + 1] is reachable
        xn, inv = back[k + 1], 1.0 / (2.0 * h_l[k])
        best = cap_l[k]
        for i in range(len(v)):
            # node k+1: p1 (xn - x) inv + c1 xn in [-a, a]; node k: p0 (xn - x) inv + c0 x in [-a, a]
            best = min(best, _upper(-p1[k][i] * inv, p1[k][i] * xn * inv + c1[k][i] * xn, a[i]),
                       _upper(c0[k][i] - p0[k][i] * inv, p0[k][i] * xn * inv, a[i]))
        back[k] = max(best, 0.0)
    back[0] = 0.0
    x = [0.0] * (n + 1)
    for k in range(n):  # the fastest x_{k+1} under back[k + 1], accelerating from x_k
        xk, inv = x[k], 1.0 / (2.0 * h_l[k])
        best = back[k + 1]
        for i in range(len(v)):
            # node k: p0 (x - xk) inv + c0 xk in [-a, a]; node k+1: p1 (x - xk) inv + c1 x in [-a, a]
            best = min(best, _upper(p0[k][i] * inv, c0[k][i] * xk - p0[k][i] * xk * inv, a[i]),
                       _upper(p1[k][i] * inv + c1[k][i], -p1[k][i] * xk * inv, a[i]))
        x[k + 1] = max(best, 0.0)
    x[n] = 0.0
    xs = np.array(x)
    root = np.sqrt(xs)
    dt = 2.0 * h / np.maximum(root[:-1] + root[1:], _EPS)
    return TimedDrive(drive, xs, np.concatenate([[0.0], np.cumsum(dt)]))


def _upper(c: float, d: float, a: float) -> float:
    """The largest x with c x + d <= a and c x + d >= -a as far as they bound x from above."""
    if c > _EPS:
        return (a - d) / c
    if c < -_EPS:
        return (-a - d) / c
    return math.inf


def _speed_cap(d1: np.ndarray, d2: np.ndarray, limits: Limits) -> np.ndarray:
    """The largest (ds/dt)^2 at each node where the velocity limits hold and some d2s/dt2 keeps every
    coordinate's acceleration within its limit (the maximum velocity curve)."""
    v, a = limits.velocity, limits.acceleration
    with np.errstate(divide="ignore", invalid="ignore"):
        cap = np.min(np.where(np.abs(d1) > _EPS, (v / np.abs(d1)) ** 2, np.inf), axis=1)
        # a coordinate with q' = 0 bounds x by a / |q''|
        still = (np.abs(d1) <= _EPS) & (np.abs(d2) > _EPS)
        cap = np.minimum(cap, np.min(np.where(still, a / np.abs(d2), np.inf), axis=1))
        # coordinates i, j: u must lie in [-A_i - rho_i x, A_i - rho_i x] for both, A = a / |q'|, rho = q'' / q'
        big = np.abs(d1) > _EPS
        A = np.where(big, a / np.abs(d1), np.inf)
        rho = np.where(big, d2 / np.where(big, d1, 1.0), 0.0)
        for i in range(d1.shape[1]):
            for j in range(d1.shape[1]):
                gap = rho[:, j] - rho[:, i]
                ok = big[:, i] & big[:, j] & (gap > _EPS)
                cap = np.where(ok, np.minimum(cap, (A[:, i] + A[:, j]) / np.where(ok, gap, 1.0)), cap)
    return cap
