"""A car space's curve queries in compiled code (#33): solving, ranking, steering along and sampling curves.

:class:`lazyground.planning.car.CarSpace` calls these with its radius and the reference point's offset; a
word is rows (turn, signed length in metres) as :func:`lazyground.planning.curves.reeds_shepp` gives them
(scaled by the radius). The numbers are those of the scalar Python the space used before (the same
operations in the same order, Python's ``max``/``min`` and stable sorting, numpy's ``%`` for wrapping): a
seed plans the same run (tests/unit/test_car_kernels.py holds each to a Python transcription of it).

Compiled lazily (the first call in a process loads numba's on-disk cache, or compiles once per machine):
:func:`warm_up` does that outside a request.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from lazyground.planning import curves
from lazyground.planning.nn import FAR
from lazyground.planning.topk import keep_smallest
from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

_WRAP = 2.0 * np.pi


@njit(cache=True)
def _ref(q, off):
    """The reference point's pose: ``off`` metres along the heading."""
    th = q[2]
    return q[0] + off * math.cos(th), q[1] + off * math.sin(th), th


@njit(cache=True)
def _relative(p, e, r):
    """Pose e in pose p's frame, positions divided by r (:func:`lazyground.planning.curves.relative`)."""
    dx, dy = e[0] - p[0], e[1] - p[1]
    c, s = math.cos(p[2]), math.sin(p[2])
    return (c * dx + s * dy) / r, (-s * dx + c * dy) / r, e[2] - p[2]


@njit(cache=True)
def _wrap(th):
    """th wrapped to [-pi, pi) (:func:`lazyground.geometry.wrap_angle`)."""
    return (th + np.pi) % _WRAP - np.pi


@njit(cache=True)
def _end(x, y, th, turn, length, r):
    """The pose after a segment of signed ``length`` metres (unit-radius kinematics, :func:`curves.advance` from
    the origin, scaled by r)."""
    s = length / r
    if turn == 0.0:
        ex, ey, eth = 0.0 + s * math.cos(th), 0.0 + s * math.sin(th), th
    elif turn > 0.0:
        ex, ey, eth = 0.0 + math.sin(th + s) - math.sin(th), 0.0 - math.cos(th + s) + math.cos(th), th + s
    else:
        ex, ey, eth = 0.0 - math.sin(th - s) + math.sin(th), 0.0 + math.cos(th - s) - math.cos(th), th - s
    return x + r * ex, y + r * ey, eth


@njit(cache=True)
def length(w):
    """A word's length: its segments' lengths summed in order."""
    total = 0.0
    for i in range(w.shape[0]):
        total += abs(w[i, 1])
    return total


@njit(cache=True)
def solve(a, b, r, off, out):
    """The shortest Reeds-Shepp word a -> b (metres) into ``out``: how many segments."""
    x, y, phi = _relative(_ref(a, off), _ref(b, off), r)
    n = curves.reeds_shepp(x, y, phi, out)
    for i in range(n):
        out[i, 1] = out[i, 1] * r
    return n


@njit(cache=True)
def closest(nodes, q, r, off, out):
    """(the row of ``nodes`` whose Reeds-Shepp word to q is shortest, its segments in ``out``).

    Rows are tried in order of a lower bound on their word's length (the reference points' distance, and
    the arc that turns the heading; stable), stopping once the bound passes the best length found."""
    k = nodes.shape[0]
    end = _ref(q, off)
    refs = np.empty((k, 3))
    bound = np.empty(k)
    order = np.empty(k, np.int64)
    for i in range(k):
        p = _ref(nodes[i], off)
        refs[i, 0], refs[i, 1], refs[i, 2] = p
        b = max(curves.hypot(p[0] - end[0], p[1] - end[1]), r * abs(curves.mod2pi(end[2] - p[2])))
        j = i  # insertion sort: equal bounds keep their order (Python's sorted)
        while j > 0 and b < bound[order[j - 1]]:
            order[j] = order[j - 1]
            j -= 1
        order[j] = i
        bound[i] = b
    w = np.empty((curves.MAX_SEGMENTS, 2))
    best, best_len, best_n = 0, math.inf, 0
    for i in order:
        if bound[i] >= best_len:
            break
        x, y, phi = _relative(refs[i], end, r)
        n = curves.reeds_shepp(x, y, phi, w)
        total = 0.0
        for j in range(n):
            total += abs(w[j, 1])
        total *= r
        if total < best_len:
            best, best_len, best_n = i, total, n
            out[:n] = w[:n]
    for j in range(best_n):
        out[j, 1] = out[j, 1] * r
    return best, best_n


@njit(cache=True)
def steer(a, w, step, r, off, q, head):
    """The pose ``step`` metres along word w from a into q, and the word's first ``step`` metres into
    ``head`` (:func:`curves.prefix`): how many segments that has."""
    th = a[2]
    x, y = a[0] + off * math.cos(th), a[1] + off * math.sin(th)
    done = 0.0
    sx, sy, sth, sturn, sgear, s0 = x, y, th, 0.0, 1.0, 0.0
    for i in range(w.shape[0]):  # the last segment starting at or before step
        seg = w[i, 1]
        if done <= step:
            sx, sy, sth, sturn, sgear, s0 = x, y, th, w[i, 0], 1.0 if seg >= 0.0 else -1.0, done
        x, y, th = _end(x, y, th, w[i, 0], seg, r)
        done += abs(seg)
    x, y, th = _end(sx, sy, sth, sturn, sgear * (step - s0), r)
    q[0], q[1], q[2] = x - off * math.cos(th), y - off * math.sin(th), _wrap(th)
    n, left = 0, step
    for i in range(w.shape[0]):
        if left <= 0.0:
            break
        seg = w[i, 1]
        head[n, 0], head[n, 1] = w[i, 0], math.copysign(min(abs(seg), left), seg)
        n += 1
        left -= abs(seg)
    return n


@njit(cache=True)
def poses(a, w, s, r, off, out):
    """Poses at arc lengths ``s`` (metres, clipped to the word's length) along word w from a, into ``out``."""
    n = w.shape[0]
    table = np.empty((max(n, 1), 6))  # per segment: arc-length offset, reference start pose, turn, gear
    th = a[2]
    x, y = a[0] + off * math.cos(th), a[1] + off * math.sin(th)
    done = 0.0
    for i in range(n):
        seg = w[i, 1]
        table[i, 0], table[i, 1], table[i, 2], table[i, 3] = done, x, y, th
        table[i, 4], table[i, 5] = w[i, 0], 1.0 if seg >= 0.0 else -1.0
        x, y, th = _end(x, y, th, w[i, 0], seg, r)
        done += abs(seg)
    if n == 0:  # (no segments: numpy's table would be empty; a == b)
        table[0, 0], table[0, 1], table[0, 2], table[0, 3], table[0, 4], table[0, 5] = 0.0, x, y, th, 0.0, 1.0
    for k in range(s.shape[0]):
        sk = min(max(s[k], 0.0), done)
        i = 0
        while i + 1 < n and table[i + 1, 0] <= sk:
            i += 1
        s0, x0, y0, th0, turn, gear = table[i, 0], table[i, 1], table[i, 2], table[i, 3], table[i, 4], table[i, 5]
        sigma = (sk - s0) * gear
        th1 = th0 + turn * sigma / r
        c1, s1 = math.cos(th1), math.sin(th1)
        if turn == 0.0:
            out[k, 0] = x0 + sigma * math.cos(th0) - off * c1
            out[k, 1] = y0 + sigma * math.sin(th0) - off * s1
        else:
            out[k, 0] = x0 + r / turn * (s1 - math.sin(th0)) - off * c1
            out[k, 1] = y0 - r / turn * (c1 - math.cos(th0)) - off * s1
        out[k, 2] = _wrap(th1)


@njit(cache=True)
def _pieces(stretched, resolution, dense_spacing):
    """Pieces a segment (its length times the origin's stretch) is sampled in (car._samples)."""
    n = max(1, int(np.ceil(stretched / resolution)))
    if resolution >= dense_spacing:
        return n
    dense = max(1, int(np.ceil(stretched / dense_spacing)))
    return dense * max(1, int(np.ceil(stretched / dense / resolution)))


@njit(cache=True)
def discretize(a, b, w, resolution, skip_first, stretch, dense_spacing, r, off):
    """Poses along word w from a to b (both ends, or b only) at most ``resolution`` metres apart, every segment
    sampled on its own (:meth:`lazyground.planning.car.CarSpace.discretize`)."""
    m = 0 if skip_first else 1
    for i in range(w.shape[0]):
        seg = abs(w[i, 1])
        if seg > 1e-12:
            m += _pieces(seg * stretch, resolution, dense_spacing)
    s = np.empty(max(m, 1))
    k = 0
    if not skip_first:
        s[0] = 0.0
        k = 1
    done = 0.0
    for i in range(w.shape[0]):
        seg = abs(w[i, 1])
        if seg <= 1e-12:
            continue
        n = _pieces(seg * stretch, resolution, dense_spacing)
        for j in range(1, n + 1):
            s[k] = done + seg * j / n
            k += 1
        done += seg
    if m == 0:  # a == b, b only
        s[0] = 0.0
    out = np.empty((s.shape[0], 3))
    poses(a, w, s, r, off, out)
    out[-1, 0], out[-1, 1], out[-1, 2] = b[0], b[1], b[2]  # the curve ends at b; drop the last ulp of drift
    return out


@njit(cache=True)
def inside(qs, lo, hi):
    """Whether every row of qs lies within [lo, hi] (the bounds with their tolerance)."""
    for i in range(qs.shape[0]):
        for j in range(qs.shape[1]):
            if not (qs[i, j] >= lo[j] and qs[i, j] <= hi[j]):
                return False
    return True


@njit(cache=True)
def nearest(points, sq, n, ids, use_ids, nodes, q, weights, k, r, off, step, out, head, q_new):
    """A car tree's node nearest q, in one call: (its index or -1, its word's segments, the head's segments,
    whether the step reaches q).

    The ``k`` nearest of the first ``n`` points of a nearest-neighbour index (:class:`lazyground.planning.nn.
    NearestNeighbors`, while it scans: points are embeddings (x, y, r cos, r sin) of ``nodes[ids[i]]``, or of
    ``nodes[i]`` without ``use_ids``; removed ones sit at FAR and are skipped) ranked as its ``nearest_k`` ranks
    them (|p|^2 + p.(-2 x), the product summed as numpy's BLAS sums four terms, then + |x|^2; equal values:
    lower index first), re-ranked by :func:`closest` (its word into ``out``). With ``step`` > 0 the pose
    ``step`` metres along that word into ``q_new`` (q itself when the word is no longer) and the word's head
    into ``head`` (:func:`steer`)."""
    th = q[2]
    x0, x1 = q[0] * weights[0], q[1] * weights[1]
    x2, x3 = weights[2] * math.cos(th), weights[2] * math.sin(th)
    xx = ((x0 * x0 + x1 * x1) + x2 * x2) + x3 * x3
    m0, m1, m2, m3 = -2.0 * x0, -2.0 * x1, -2.0 * x2, -2.0 * x3
    vals = np.empty(k)
    best_k = np.empty(k, np.int64)
    m = 0
    for i in range(n):
        if points[i, 0] == FAR:
            continue
        g = (sq[i] + ((points[i, 0] * m0 + points[i, 2] * m2) + (points[i, 1] * m1 + points[i, 3] * m3))) + xx
        m = keep_smallest(vals, best_k, m, k, g, i)
    if m == 0:
        return -1, 0, 0, False
    cands = np.empty((m, 3))
    for c in range(m):
        j = ids[best_k[c]] if use_ids else best_k[c]
        best_k[c] = j
        cands[c, 0], cands[c, 1], cands[c, 2] = nodes[j, 0], nodes[j, 1], nodes[j, 2]
    best, nw = closest(cands, q, r, off, out)
    if step <= 0.0:
        return best_k[best], nw, 0, False
    if length(out[:nw]) <= step:
        q_new[0], q_new[1], q_new[2] = q[0], q[1], q[2]
        return best_k[best], nw, 0, True
    return best_k[best], nw, steer(cands[best], out[:nw], step, r, off, q_new, head), False


_loaded: bool | None = None


def warm_up() -> bool:
    """Load (or compile, once per machine) the kernels a car's planner calls, now rather than in its search
    (:func:`lazyground.planning.car.car_space` calls it): whether this call compiled them. Idempotent.

    Loading them from numba's cache takes ~1-2 s at load 16 on 2 cores (most of it numba's own start-up, paid once
    per process by the first cached kernel it loads); compiling them ~64 s there."""
    global _loaded
    if _loaded is not None:
        return False
    a, b, w = np.zeros(3), np.array([1.0, 0.5, 0.3]), np.empty((curves.MAX_SEGMENTS, 2))
    n = solve(a, b, 1.0, -0.5, w)
    length(w[:n])
    steer(a, w[:n], 0.1, 1.0, -0.5, np.empty(3), np.empty((curves.MAX_SEGMENTS, 2)))
    poses(a, w[:n], np.zeros(1), 1.0, -0.5, np.empty((1, 3)))
    inside(discretize(a, b, w[:n], 0.05, True, 1.1, 0.1, 1.0, -0.5), np.zeros(3), np.ones(3))
    nearest(np.zeros((1, 4)), np.zeros(1), 1, np.zeros(1, np.int64), False, np.zeros((1, 3)), b, np.ones(3), 5, 1.0,
            -0.5, 0.5, w, np.empty((curves.MAX_SEGMENTS, 2)), np.empty(3))
    _loaded = any(sum(k.stats.cache_misses.values()) for k in (solve, length, steer, poses, discretize, inside, nearest))
    return _loaded
