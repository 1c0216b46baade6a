"""An edge check's glue in compiled code (#31): one call per edge instead of one per step and piece.

:func:`edge_open` does what :meth:`lazyground.drake.checker.DrakeChecker` did in Python around
:func:`lazyground.drake.sphere_kernels.first_open` (~10 µs an edge on Fetch, as much as the kernel): the
plant positions of both ends (b on the shorter arc from a), the step count from the weighted distance, the
steps' order (:func:`step_order`, which the checker also reads past a step left open), and the certifier's
test of each step with early exit at the first one it does not prove free. The checker decides that step (SceneGraph) and goes on with ``first_open``, as before.

The step count must be Drake's: ``ceil(d / resolution)`` with d Drake's weighted distance (a planner's
steps end exactly one step length away, so d / resolution sits on an integer and its last bit decides the
count). :func:`squared_norm` sums the squares in the order Eigen's vectorised reduction does, with the
packet width the installed Drake was built for (:func:`eigen_packet` finds it once per process by comparing
with Drake's own distance); where none matches, the checker gives the count from Drake's distance.

numba's on-disk cache keys a function on its own file's text only: a change to the sphere_kernels functions
:func:`edge_open` inlines (the views, the row test) reaches it once this file's text changes too.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from lazyground.drake.sphere_kernels import block_views, open_pairs_row, scratch_views, tree_views
from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

SEQUENCE, BISECTION, INTERIOR_FIRST = 0, 1, 2  # the step orders (an edge's free fraction; edge_free; a part of one)
ALL_FREE = -1  # edge_open's answer: every step asked about is certified free
PACKETS = (2, 4, 1, 8)  # Eigen's packet widths in doubles (SSE2/NEON, AVX, none, AVX-512), the likeliest first


@njit(cache=True)
def squared_norm(v, packet):
    """sum(v * v) summed as Eigen's ``squaredNorm`` on aligned data sums it with packets of ``packet`` doubles
    (Eigen/src/Core/Redux.h, linear vectorised traversal: two packet accumulators, their sum, one packet more,
    the packet's lanes halved pairwise, then the tail in sequence; 1: in sequence)."""
    size = len(v)
    whole = size // packet * packet
    if packet == 1 or whole == 0:
        res = v[0] * v[0]
        for i in range(1, size):
            res += v[i] * v[i]
        return res
    acc = np.empty(2 * packet)
    for lane in range(packet):
        acc[lane] = v[lane] * v[lane]
    if whole > packet:
        pairs = size // (2 * packet) * (2 * packet)
        for lane in range(packet):
            acc[packet + lane] = v[packet + lane] * v[packet + lane]
        for i in range(2 * packet, pairs, 2 * packet):
            for lane in range(packet):
                acc[lane] += v[i + lane] * v[i + lane]
                acc[packet + lane] += v[i + packet + lane] * v[i + packet + lane]
        for lane in range(packet):
            acc[lane] += acc[packet + lane]
        if whole > pairs:
            for lane in range(packet):
                acc[lane] += v[pairs + lane] * v[pairs + lane]
    width = packet
    while width > 1:  # predux: the lower half plus the upper half, down to one lane
        width //= 2
        for lane in range(width):
            acc[lane] += acc[width + lane]
    res = acc[0]
    for i in range(whole, size):
        res += v[i] * v[i]
    return res


def eigen_packet(distance, weights: np.ndarray, rng: np.random.Generator, trials: int = 200) -> int:
    """The packet width (PACKETS) whose :func:`squared_norm` gives ``distance`` (Drake's
    ``ComputeConfigurationDistance``) bit for bit on ``trials`` random pairs of configurations; 0 when none does."""
    weights = np.asarray(weights, float)
    pairs = [(rng.uniform(-3, 3, len(weights)), rng.uniform(-3, 3, len(weights)) * rng.choice([1e-3, 1.0, 1e2]))
             for _ in range(trials)]
    want = [distance(a, b) for a, b in pairs]
    for packet in PACKETS:
        if all(np.sqrt(squared_norm((b - a) * weights, packet)) == d for (a, b), d in zip(pairs, want)):
            return packet
    return 0


@njit(cache=True)
def step_order(n, mode):
    """Steps 0..n in the order ``mode`` visits them: SEQUENCE 0, 1, .., n; BISECTION the end n, the start, then
    the middles of ever finer halvings (level by level, left to right); INTERIOR_FIRST those middles, then 0, n."""
    out = np.empty(n + 1, np.int64)
    if mode == SEQUENCE:
        for k in range(n + 1):
            out[k] = k
        return out
    lo, hi = np.empty(n + 1, np.int64), np.empty(n + 1, np.int64)  # this level's intervals
    nlo, nhi = np.empty(n + 1, np.int64), np.empty(n + 1, np.int64)  # the next level's
    if mode == BISECTION:
        out[0], out[1], count = n, 0, 2
    else:
        out[n - 1], out[n], count = 0, n, 0
    lo[0], hi[0], m = 0, n, 1
    while m > 0:
        k = 0
        for i in range(m):
            if hi[i] - lo[i] > 1:
                mid = (lo[i] + hi[i]) // 2
                out[count] = mid
                count += 1
                nlo[k], nhi[k], nlo[k + 1], nhi[k + 1] = lo[i], mid, mid, hi[i]
                k += 2
        lo, hi, nlo, nhi = nlo, nhi, lo, hi
        m = k
    return out


@njit(cache=True)
def edge_open(fd, idata, work, pairs, state, qab, planned, edata, packet, a, b, resolution, mode, first, stop, steps):
    """The first position p of the steps' order (from ``first``, before ``stop``; -1: to the end) whose
    configuration is not certified free (its code in ``pairs[-1]``, its open pairs before), or ALL_FREE.
    ``steps`` > 0: the step count (else computed, Drake's: ``packet`` is :func:`eigen_packet`'s).

    ``a``, ``b``: planned coordinates; ``planned``: their indices in the plant's positions; ``edata``: the plant's
    positions at the start (unplanned ones stay there), the metric weights over them, and per planned coordinate
    1.0 where it wraps. Writes both ends' plant positions into ``qab`` (b on the shorter arc from a, as
    ``a + space.difference(a, b)``) and the step count into ``state[0]``."""
    nq, nplan = qab.shape[1], len(planned)
    qa, qb = qab[0], qab[1]
    for j in range(nq):
        qa[j] = edata[j]
        qb[j] = edata[j]
    for i in range(nplan):
        d = b[i] - a[i]
        if edata[2 * nq + i] != 0.0:
            d = (d + np.pi) % (2 * np.pi) - np.pi  # lazyground.geometry.wrap_angle
        qa[planned[i]] = a[i]
        qb[planned[i]] = a[i] + d
    n = steps
    if n <= 0:
        v = np.empty(nq)
        for j in range(nq):
            v[j] = (qb[j] - qa[j]) * edata[nq + j]
        n = max(1, int(np.ceil(np.sqrt(squared_norm(v, packet)) / resolution)))
    state[0] = n
    end = n + 1 if stop < 0 else min(stop, n + 1)  # len(step_order(n, mode)) is n + 1
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = scratch_views(idata, work)
    tree, blocks = tree_views(fd, idata), block_views(fd, idata)
    q = np.empty(nq)
    cap = len(pairs) - 1
    p = first
    if mode == BISECTION and p == 0 and end > 0:  # bisection's first step is the end n: most of a planner's
        # edges stop there (88 % on fetch_boxes_3), so the order is made only past it (~0.3 µs, #31)
        t = n / n
        for j in range(nq):
            q[j] = qa[j] + t * (qb[j] - qa[j])
        c = open_pairs_row(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, sph, done, W, A, gap, pairs, cap, 0.0)
        if c != 0:
            pairs[-1] = c
            return 0
        p = 1
    order = step_order(n, mode)
    for p in range(p, end):
        t = order[p] / n
        for j in range(nq):
            q[j] = qa[j] + t * (qb[j] - qa[j])
        c = open_pairs_row(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, sph, done, W, A, gap, pairs, cap, 0.0)
        if c != 0:
            pairs[-1] = c
            return p
    return ALL_FREE


def edge_data(q_full: np.ndarray, weights: np.ndarray, wrap: np.ndarray) -> np.ndarray:
    """:func:`edge_open`'s ``edata``: start positions, weights over the plant's positions, wrap per planned one."""
    return np.concatenate([np.asarray(q_full, float), np.asarray(weights, float), np.asarray(wrap, float)])
