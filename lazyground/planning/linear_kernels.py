"""The planner loop's nearest-neighbour scan and steering in compiled code, for linear spaces (#31).

A space whose coordinates are their own embedding (no angles, unit weights: every arm here) keeps its
tree's nodes in the nearest-neighbour index as they are, so one call can find the nearest node and
steer from it (:func:`nearest_steer`): one numba call in place of ~10 µs of numpy calls a step.

The numbers are numpy's where numpy's are in order: steering is b - a, its squared norm summed in
coordinate order (np.dot below 16 entries), a + (step / d) (b - a) in two roundings, as
:meth:`lazyground.planning.space.ConfigSpace.steer`. The scan ranks |p|^2 + p.(-2 x) as
:meth:`lazyground.planning.nn.NearestNeighbors._scan` does, summing p.(-2 x) in coordinate order
where BLAS blocks it: the values can differ in the last bit, so two points within a rounding of
the same distance may swap (0 of 3,000 random scans ranked differently).

The module is imported only when a linear space's tree is built (a car never loads it); the import
compiles the kernels or loads numba's on-disk cache (once per process): :func:`warm_up` reports it, and
the Drake world build calls it with the collision kernels' (lazyground.drake.compiled), so no request pays it.
"""

from __future__ import annotations

import time

import numpy as np
from numba import njit

from lazyground.planning.topk import keep_smallest
from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

_T0 = time.perf_counter()
_warm_s: float | None = None


# explicit signatures: numba compiles (or loads) them at import, never at a call; an argument of another
# layout or a read-only array raises TypeError, and the caller takes the numpy path instead
_P, _V, _I = "float64[:, ::1]", "float64[::1]", "int64[::1]"


@njit(f"int64({_P}, {_V}, int64, {_V})", cache=True)
def nearest(points, sq, n, x):
    """Index of the first of the ``n`` first points with the smallest |p|^2 + p.(-2 x), -1 if n is 0."""
    d = points.shape[1]
    m2x = np.empty(d)
    for j in range(d):
        m2x[j] = -2.0 * x[j]
    best, best_g = -1, np.inf
    for i in range(n):
        s = 0.0
        for j in range(d):
            s += points[i, j] * m2x[j]
        g = sq[i] + s
        if g < best_g:
            best, best_g = i, g
    return best


@njit(f"int64({_P}, {_V}, int64, {_V}, int64, {_I})", cache=True)
def nearest_k(points, sq, n, x, k, out):
    """The up to ``k`` nearest of the ``n`` first points into ``out``, nearest first (ties: lower index
    first); returns how many."""
    d = points.shape[1]
    m2x = np.empty(d)
    for j in range(d):
        m2x[j] = -2.0 * x[j]
    vals = np.empty(k)
    m = 0
    for i in range(n):
        s = 0.0
        for j in range(d):
            s += points[i, j] * m2x[j]
        m = keep_smallest(vals, out, m, k, sq[i] + s, i)
    return m


@njit(f"boolean({_V}, {_V}, float64, {_V})", cache=True)
def steer(a, b, step, out):
    """out = a moved towards b by at most ``step`` (unit weights); returns whether it reached b (out = b)."""
    d = a.shape[0]
    s = 0.0
    for j in range(d):
        v = b[j] - a[j]
        out[j] = v
        s += v * v
    dist = np.sqrt(s)
    if dist <= step:
        for j in range(d):
            out[j] = b[j]
        return True
    f = step / dist
    for j in range(d):
        out[j] = out[j] * f + a[j]
    return False


@njit(f"int64({_P}, {_V}, int64, {_V}, float64, {_V})", cache=True)
def nearest_steer(points, sq, n, x, step, out):
    """The nearest point's index (:func:`nearest`; -1 if none) and ``out`` steered from it towards x
    (:func:`steer`): 2 i + 1 when the step reaches x, 2 i when it stops short."""
    i = nearest(points, sq, n, x)
    if i < 0:
        return -1
    return 2 * i + (1 if steer(points[i], x, step, out) else 0)


@njit(f"Tuple((float64[:, ::1], int64[::1]))({_P}, {_I}, float64)", cache=True)
def discretize_path(path, ks, resolution):
    """The path's segments ``ks`` (ascending) at ``resolution``, a vertex shared by two of them once, and each
    row's segment: :meth:`lazyground.planning.space.ConfigSpace.discretize_path`'s numbers (unit weights):
    n = max(1, ceil(|b - a| / resolution)) with the norm summed in coordinate order, rows a + (i / n) (b - a)."""
    m, d = ks.shape[0], path.shape[1]
    ns = np.empty(m, np.int64)
    total = 0
    for r in range(m):
        k = ks[r]
        s = 0.0
        for j in range(d):
            v = path[k + 1, j] - path[k, j]
            s += v * v
        n = max(1, int(np.ceil(np.sqrt(s) / resolution)))
        ns[r] = n
        total += n + (0 if r > 0 and ks[r - 1] == k - 1 else 1)
    qs = np.empty((total, d))
    owner = np.empty(total, np.int64)
    row = 0
    for r in range(m):
        k, n = ks[r], ns[r]
        for i in range(1 if r > 0 and ks[r - 1] == k - 1 else 0, n + 1):
            t = i / n
            for j in range(d):
                qs[row, j] = path[k, j] + t * (path[k + 1, j] - path[k, j])
            owner[row] = k
            row += 1
    return qs, owner


@njit(f"void({_P}, {_V})", cache=True)
def segment_lengths(path, out):
    """out[k] = |path[k + 1] - path[k]| summed in coordinate order (ConfigSpace.distance, unit weights)."""
    for k in range(path.shape[0] - 1):
        s = 0.0
        for j in range(path.shape[1]):
            v = path[k + 1, j] - path[k, j]
            s += v * v
        out[k] = np.sqrt(s)


@njit(f"boolean({_P}, {_V}, {_V})", cache=True)
def all_inside(qs, lower, upper):
    """Whether every row lies within [lower - 1e-9, upper + 1e-9] (motion_validator.samples_free's test)."""
    d = qs.shape[1]
    for j in range(d):
        lo, hi = lower[j] - 1e-9, upper[j] + 1e-9
        for i in range(qs.shape[0]):
            if not (qs[i, j] >= lo and qs[i, j] <= hi):
                return False
    return True


def warm_up() -> tuple[float, bool]:
    """(seconds this process spent getting the kernels at import, whether it compiled them rather than
    loading numba's cache); the first call only, (0.0, False) after it."""
    global _warm_s
    if _warm_s is not None:
        return 0.0, False
    _warm_s = _IMPORT_S
    return _warm_s, _COMPILED


_IMPORT_S = time.perf_counter() - _T0
_COMPILED = any(sum(k.stats.cache_misses.values()) for k in (nearest, nearest_k, steer, nearest_steer,
                                                                    discretize_path, segment_lengths, all_inside))
