"""Goal sampling's inner loops, compiled with numba (#31): the batch IK solver's damped least squares
(:func:`solve_rows`) and the hand probe's test of targets (:func:`probe_rows`).

:func:`solve_rows` runs :func:`lazyground.drake.ik.batch.solve_batch`'s method row by
row: forward kinematics and the geometric Jacobian of the chain (as
:meth:`~lazyground.drake.chain.Chain.forward`), the error outside the tolerance, a
Levenberg-Marquardt step through a 6x6 Cholesky solve, joints at a limit held, and
the step kept only when it lowers the error. A row stops when it is within SETTLE
of its tolerance. The numpy batch paid one array operation per iteration for all
rows and kept iterating while any row was live (~70 µs a row on Fetch); a row here
costs ~1 µs an iteration. ``cache=True``: compiled once per machine
(:func:`lazyground.drake.compiled.warm_up` loads them with the collision kernels).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from lazyground.drake.sphere_kernels import solid_distance
from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

PRISMATIC_KIND = 1  # lazyground.drake.chain.PRISMATIC (the caller checks)


@njit(cache=True)
def _forward(q, X_before, X_after, kinds, T, axes, origins, X, J, jacobian, tmp):
    """World pose X (4, 4) of the chain's end at ``q``; with ``jacobian`` also J (6, n), rows (angular; linear)."""
    n = len(kinds)
    for r in range(3):
        for c in range(4):
            T[r, c] = X_before[0, r, c] if n else (1.0 if r == c else 0.0)
    for k in range(n):
        if k:
            for r in range(3):
                for c in range(4):
                    tmp[c] = T[r, 0] * X_before[k, 0, c] + T[r, 1] * X_before[k, 1, c] + T[r, 2] * X_before[k, 2, c] \
                        + T[r, 3] * X_before[k, 3, c]
                for c in range(4):
                    T[r, c] = tmp[c]
        for r in range(3):
            axes[k, r] = T[r, 2]
            origins[k, r] = T[r, 3]
        if kinds[k] == PRISMATIC_KIND:
            for r in range(3):
                T[r, 3] += T[r, 2] * q[k]
        else:  # T @ Rz(q): turn the first two columns
            cq, sq = math.cos(q[k]), math.sin(q[k])
            for r in range(3):
                x, y = T[r, 0], T[r, 1]
                T[r, 0] = x * cq + y * sq
                T[r, 1] = y * cq - x * sq
    for r in range(3):
        for c in range(4):
            X[r, c] = T[r, 0] * X_after[0, c] + T[r, 1] * X_after[1, c] + T[r, 2] * X_after[2, c] + T[r, 3] * X_after[3, c]
    X[3, 0], X[3, 1], X[3, 2], X[3, 3] = 0.0, 0.0, 0.0, 1.0
    if not jacobian:
        return
    for k in range(n):
        ax, ay, az = axes[k, 0], axes[k, 1], axes[k, 2]
        if kinds[k] == PRISMATIC_KIND:
            J[0, k], J[1, k], J[2, k] = 0.0, 0.0, 0.0
            J[3, k], J[4, k], J[5, k] = ax, ay, az
        else:
            rx, ry, rz = X[0, 3] - origins[k, 0], X[1, 3] - origins[k, 1], X[2, 3] - origins[k, 2]
            J[0, k], J[1, k], J[2, k] = ax, ay, az
            J[3, k], J[4, k], J[5, k] = ay * rz - az * ry, az * rx - ax * rz, ax * ry - ay * rx


@njit(cache=True)
def _pose_error(X, T, e, R):
    """e[0:3] = rotation vector taking X's orientation to T's, e[3:6] = T's position less X's; returns the angle."""
    for r in range(3):
        for c in range(3):
            R[r, c] = T[r, 0] * X[c, 0] + T[r, 1] * X[c, 1] + T[r, 2] * X[c, 2]  # R_T R_X^T
    cos = min(max((R[0, 0] + R[1, 1] + R[2, 2] - 1.0) / 2.0, -1.0), 1.0)
    angle = math.acos(cos)
    s0, s1, s2 = 0.5 * (R[2, 1] - R[1, 2]), 0.5 * (R[0, 2] - R[2, 0]), 0.5 * (R[1, 0] - R[0, 1])
    sin = math.sin(angle)
    ratio = angle / max(sin, 1e-9) if sin > 1e-9 else 1.0
    e[0], e[1], e[2] = s0 * ratio, s1 * ratio, s2 * ratio
    if cos < -0.999 and math.sqrt(s0 * s0 + s1 * s1 + s2 * s2) < 1e-3:  # the axis from R + I's longest column
        best, col = -1.0, 0
        for c in range(3):
            norm = math.sqrt((R[0, c] + (c == 0)) ** 2 + (R[1, c] + (c == 1)) ** 2 + (R[2, c] + (c == 2)) ** 2)
            if norm > best:
                best, col = norm, c
        for r in range(3):
            e[r] = math.pi * (R[r, col] + (r == col)) / best
    for r in range(3):
        e[3 + r] = T[r, 3] - X[r, 3]
    return angle


@njit(cache=True)
def _excess(X, T, ptol, otol, settle, weight, e, R):
    """The weighted (rotation; position) error outside the tolerance into e; (its squared norm, within settle of it)."""
    angle = _pose_error(X, T, e, R)
    shrink = max(0.0, 1.0 - otol / max(angle, 1e-12))
    worst, rot = 0.0, 0.0
    for r in range(3):
        e[r] *= shrink
        rot += e[r] * e[r]
        d = e[3 + r]
        e[3 + r] = d - min(max(d, -ptol), ptol)
        worst = max(worst, abs(e[3 + r]))
    done = worst <= settle * ptol and rot <= (settle * otol) ** 2
    cost = 0.0
    for r in range(6):
        e[r] *= weight[r]
        cost += e[r] * e[r]
    return cost, done


@njit(cache=True)
def _step(J, e, d, held, step, A, L, y):
    """step = J^T (J J^T + d^2 I)^-1 e with the ``held`` joints' columns of J taken as zero (6x6 Cholesky)."""
    n = J.shape[1]
    for i in range(6):
        for j in range(i + 1):
            s = 0.0
            for k in range(n):
                if not held[k]:
                    s += J[i, k] * J[j, k]
            A[i, j] = s
        A[i, i] += d * d
    for i in range(6):
        for j in range(i + 1):
            s = A[i, j]
            for k in range(j):
                s -= L[i, k] * L[j, k]
            if i == j:
                L[i, i] = math.sqrt(max(s, 1e-300))
            else:
                L[i, j] = s / L[j, j]
    for i in range(6):
        s = e[i]
        for k in range(i):
            s -= L[i, k] * y[k]
        y[i] = s / L[i, i]
    for i in range(5, -1, -1):
        s = y[i]
        for k in range(i + 1, 6):
            s -= L[k, i] * y[k]
        y[i] = s / L[i, i]
    for k in range(n):
        s = 0.0
        if not held[k]:
            for i in range(6):
                s += J[i, k] * y[i]
        step[k] = s


@njit(cache=True)
def _weigh(J, weight):
    """J's rows times their error weights (rotation rows in m per rad)."""
    for i in range(6):
        for k in range(J.shape[1]):
            J[i, k] *= weight[i]


@njit(cache=True)
def limit_row(q, lower, upper, wrap, out):
    """q (n,) brought within the limits into ``out``: bounded joints clipped, continuous ones wrapped."""
    for k in range(len(q)):
        if wrap[k]:
            span = upper[k] - lower[k]
            out[k] = lower[k] + (q[k] - lower[k]) % span
        else:
            out[k] = min(max(q[k], lower[k]), upper[k])


@njit(cache=True)
def solve_rows(q0, targets, X_before, X_after, kinds, free, lower, upper, wrap, ptol, otol, iterations,
               damping0, min_damping, max_damping, settle, weight, max_dp, max_angle, q_out, done_out, met_out):
    """Damped least squares per row from ``q0`` (B, n) towards ``targets`` (B, 4, 4): answers into ``q_out``,
    converged (within ``settle`` of the tolerance) into ``done_out``, met within (``max_dp``, ``max_angle``)
    by the answer's pose into ``met_out``."""
    B, n = q0.shape
    T = np.empty((3, 4))
    axes, origins = np.empty((n, 3)), np.empty((n, 3))
    X, X_t = np.empty((4, 4)), np.empty((4, 4))
    J, J_t = np.empty((6, n)), np.empty((6, n))
    e, e_t = np.empty(6), np.empty(6)
    q, q_try, raw, step = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    held, blocked = np.empty(n, np.bool_), np.empty(n, np.bool_)
    tmp, R, A, L, y = np.empty(4), np.empty((3, 3)), np.empty((6, 6)), np.zeros((6, 6)), np.empty(6)  # scratch
    for k in range(n):
        held[k] = not free[k]
    for b in range(B):
        limit_row(q0[b], lower, upper, wrap, q)
        target = targets[b]
        _forward(q, X_before, X_after, kinds, T, axes, origins, X, J, True, tmp)
        _weigh(J, weight)
        cost, done = _excess(X, target, ptol, otol, settle, weight, e, R)
        d = damping0
        for _ in range(iterations):
            if done:
                break
            _step(J, e, d, held, step, A, L, y)
            # a joint at a limit that the step pushes further out is held: the step is solved again without it
            again = False
            for k in range(n):
                blocked[k] = held[k] or (not wrap[k] and ((q[k] <= lower[k] and step[k] < 0) or (q[k] >= upper[k] and step[k] > 0)))
                again |= blocked[k] and not held[k]
            if again:
                _step(J, e, d, blocked, step, A, L, y)
            for k in range(n):
                raw[k] = q[k] + step[k]
            limit_row(raw, lower, upper, wrap, q_try)
            _forward(q_try, X_before, X_after, kinds, T, axes, origins, X_t, J_t, True, tmp)
            _weigh(J_t, weight)
            cost_t, done_t = _excess(X_t, target, ptol, otol, settle, weight, e_t, R)
            if cost_t < cost:
                q[:], X[:], J[:], e[:] = q_try, X_t, J_t, e_t
                cost, done = cost_t, done_t
                d = max(d * 0.5, min_damping)
            else:
                d = min(d * 4.0, max_damping)
        q_out[b] = q
        done_out[b] = done
        angle = _pose_error(X, target, e, R)
        met_out[b] = math.sqrt(e[3] * e[3] + e[4] * e[4] + e[5] * e[5]) <= max_dp and angle <= max_angle


@njit(cache=True)
def probe_rows(X_WT, points, R_WS, p_WS, half, rounding, cylinder, limit, near, out):
    """:meth:`lazyground.drake.ik.hand_probe.HandProbe.blocked` per target pose (B, 4, 4) into ``out`` (B,):
    some probe point, placed by the target, closer to an obstacle's solid than its limit there."""
    for b in range(len(X_WT)):
        out[b] = False
        for k in range(len(R_WS)):
            v0, v1, v2 = X_WT[b, 0, 3] - p_WS[k, 0], X_WT[b, 1, 3] - p_WS[k, 1], X_WT[b, 2, 3] - p_WS[k, 2]
            o0 = v0 * R_WS[k, 0, 0] + v1 * R_WS[k, 1, 0] + v2 * R_WS[k, 2, 0]  # the hand's origin in the solid's frame
            o1 = v0 * R_WS[k, 0, 1] + v1 * R_WS[k, 1, 1] + v2 * R_WS[k, 2, 1]
            o2 = v0 * R_WS[k, 0, 2] + v1 * R_WS[k, 1, 2] + v2 * R_WS[k, 2, 2]
            if not solid_distance(o0, o1, o2, half[k, 0], half[k, 1], half[k, 2], rounding[k], cylinder[k]) < near[k]:
                continue
            for p in range(len(points)):
                x, y, z = points[p, 0], points[p, 1], points[p, 2]
                w0 = X_WT[b, 0, 0] * x + X_WT[b, 0, 1] * y + X_WT[b, 0, 2] * z  # the point's offset, in world
                w1 = X_WT[b, 1, 0] * x + X_WT[b, 1, 1] * y + X_WT[b, 1, 2] * z
                w2 = X_WT[b, 2, 0] * x + X_WT[b, 2, 1] * y + X_WT[b, 2, 2] * z
                l0 = o0 + w0 * R_WS[k, 0, 0] + w1 * R_WS[k, 1, 0] + w2 * R_WS[k, 2, 0]
                l1 = o1 + w0 * R_WS[k, 0, 1] + w1 * R_WS[k, 1, 1] + w2 * R_WS[k, 2, 1]
                l2 = o2 + w0 * R_WS[k, 0, 2] + w1 * R_WS[k, 1, 2] + w2 * R_WS[k, 2, 2]
                if solid_distance(l0, l1, l2, half[k, 0], half[k, 1], half[k, 2], rounding[k], cylinder[k]) < limit[k, p]:
                    out[b] = True
                    break
            if out[b]:
                break


def warm_up() -> bool:
    """Compile (or load from numba's cache) the kernels with the argument types their callers pass, on toy
    data (a one-joint chain, one probe point and box); whether any compiled (no usable cache)."""
    eye, f, b = np.eye(4), np.zeros(1), np.zeros(1, np.bool_)
    solve_rows(np.zeros((1, 1)), eye[None].copy(), eye[None].copy(), eye.copy(), np.zeros(1, np.int64), ~b, f - 1.0,
               f + 1.0, b, 0.002, 0.01, 1, 0.05, 1e-6, 1e3, 0.05, np.ones(6), 0.002, 0.01, np.zeros((1, 1)), b.copy(), b.copy())
    probe_rows(eye[None].copy(), np.zeros((1, 3)), np.eye(3)[None].copy(), np.zeros((1, 3)), np.ones((1, 3)), f.copy(),
               b.copy(), np.zeros((1, 1)), np.ones(1), b.copy())
    return bool(sum(solve_rows.stats.cache_misses.values()) + sum(probe_rows.stats.cache_misses.values()))
