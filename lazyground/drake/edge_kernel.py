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

from lazyground.drake.sphere_kernels import (COLLIDES, block_views, c_view, open_pairs_row, row_inline,
                                             scratch_views, tree_views)
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


@njit(cache=True, inline="always")
def _step_count(qa, qb, edata, packet, resolution, steps):
    """``steps`` when given (> 0), else Drake's: max(1, ceil(weighted distance / resolution)), summed as Drake sums."""
    if steps > 0:
        return steps
    nq = len(qa)
    v = np.empty(nq)
    for j in range(nq):
        v[j] = (qb[j] - qa[j]) * edata[nq + j]
    return max(1, int(np.ceil(np.sqrt(squared_norm(v, packet)) / resolution)))


@njit(cache=True, inline="always")
def edge_open(fd, idata, work, pairs, state, qab, planned, edata, packet, a, b, resolution, mode, first, stop, steps):
    """The first position p of the steps' order (from ``first``, before ``stop``; -1: to the end) whose
    configuration is not certified free (its code in ``pairs[-1]``, its open pairs before), or ALL_FREE.
    ``steps`` > 0: the step count (else computed, Drake's: ``packet`` is :func:`eigen_packet`'s).

    ``a``, ``b``: planned coordinates; ``planned``: their indices in the plant's positions; ``edata``: the plant's
    positions at the start (unplanned ones stay there), the metric weights over them, and per planned coordinate
    1.0 where it wraps. Writes both ends' plant positions into ``qab[:2]`` (b on the shorter arc from a, as
    ``a + space.difference(a, b)``; ``qab[2]``: the step's, scratch) and the step count into ``state[0]`` (0 when
    bisection's first step, the end, is proven colliding: the count is not needed then). Inlined into
    :func:`edge_call` (a call between compiled functions passes every view's fields: ~0.2 µs, #31)."""
    nq, nplan = qab.shape[1], len(planned)
    qa, qb, q = qab[0], qab[1], qab[2]
    for j in range(nq):
        qa[j] = edata[j]
        qb[j] = edata[j]
    for i in range(nplan):
        d = b[i] - a[i]
        if edata[2 * nq + i] != 0.0:
            d = (d + np.pi) % (2 * np.pi) - np.pi  # lazyground.geometry.wrap_angle
        qa[planned[i]] = a[i]
        qb[planned[i]] = a[i] + d
    Rs, ps, Rb, pb, centre, sph, done, W, A, gap = scratch_views(idata, work)
    tree, blocks = tree_views(fd, idata), block_views(fd, idata)
    cap = len(pairs) - 1
    p = first
    # bisection's first step is the end (t = n / n = 1 for every n): most of a planner's edges stop there (88 % on
    # fetch_boxes_3), so the order (~0.3 µs) and, where the end is proven colliding, the step count (~0.3 µs) are
    # not needed then (#31). One loop and one row test for both: each inlined row test is ~1/6 of the kernels'
    # first compile (#31)
    end_first = mode == BISECTION and p == 0 and stop != 0
    n, end, order = 0, 0, c_view(state, 0, (0,))  # the count (>= 1), the end and the order: made when needed
    while True:
        if n == 0 and not end_first:
            n = _step_count(qa, qb, edata, packet, resolution, steps)
            state[0] = n
            end = n + 1 if stop < 0 else min(stop, n + 1)  # len(step_order(n, mode)) is n + 1
            order = step_order(n, mode)
        if not end_first and p >= end:
            return ALL_FREE
        t = 1.0 if end_first else order[p] / n
        for j in range(nq):
            q[j] = qa[j] + t * (qb[j] - qa[j])
        c = open_pairs_row(q, idata, tree, blocks, Rs, ps, Rb, pb, centre, sph, done, W, A, gap, pairs, cap, 0.0)
        if c != 0:
            pairs[-1] = c
            if end_first:
                state[0] = 0 if c == COLLIDES else _step_count(qa, qb, edata, packet, resolution, steps)
            return p
        end_first = False
        p += 1


# A checker's call data (call_data): the certifier's arrays and an edge's in one float and one int array, so that a
# call passes two arrays besides its own: numba's dispatcher types and unboxes every argument on every call (~0.1 µs
# an array; edge_open's 16 arguments cost ~1.3 µs a call, #31). The int array ends in CALL_HEAD offsets and sizes:
_WORK, _EDATA, _QAB, _QC, _PAIRS, _NPAIRS, _STATE, _PLANNED, _NPLAN, _NQ, _PACKET = range(11)
CALL_HEAD = 11


def call_data(fd: np.ndarray, idata: np.ndarray, work_size: int, edata: np.ndarray, planned: np.ndarray, packet: int,
              cap: int) -> tuple[np.ndarray, np.ndarray]:
    """(F, I) for :func:`edge_call` and :func:`config_call`: F = the certifier's float data, its scratch (``work_size``
    floats), ``edata`` (:func:`edge_data`), an edge's two ends and its step's, and one configuration's plant positions; I = its int data,
    the open pairs (``cap`` and the code), the step count, the planned indices, then the offsets. Both arrays
    start with the certifier's, whose offsets count from there."""
    planned = np.asarray(planned, np.int64)
    nq = (len(edata) - len(planned)) // 2
    sizes_f = (len(fd), work_size, len(edata), 3 * nq, nq)
    at_f = np.cumsum((0,) + sizes_f)
    F = np.concatenate([fd, np.zeros(work_size), edata, np.zeros(4 * nq)])
    at_i = np.cumsum((0, len(idata), cap + 1, 1, len(planned)))
    head = np.zeros(CALL_HEAD, np.int64)
    head[[_WORK, _EDATA, _QAB, _QC]] = at_f[1:5]
    head[[_PAIRS, _STATE, _PLANNED]] = at_i[1:4]
    head[_NPAIRS], head[_NPLAN], head[_NQ], head[_PACKET] = cap + 1, len(planned), nq, packet
    I = np.concatenate([idata, np.zeros(cap + 2, np.int64), planned, head])
    return F, I


def call_blocks(F: np.ndarray, I: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Views of the blocks the kernels write in a checker's call data (:func:`call_data`): (open pairs then the
    code, the step count, an edge's ends' plant positions (2, nq), a single check's plant positions)."""
    h = len(I) - CALL_HEAD
    nq = I[h + _NQ]
    return (I[I[h + _PAIRS]:I[h + _PAIRS] + I[h + _NPAIRS]], I[I[h + _STATE]:I[h + _STATE] + 1],
            F[I[h + _QAB]:I[h + _QAB] + 2 * nq].reshape(2, nq), F[I[h + _QC]:I[h + _QC] + nq])


@njit(cache=True, inline="always")
def _call_views(F, I):
    """(work, edata, ends, one configuration, open pairs, step count, planned indices, packet) in F and I (:func:`call_data`)."""
    h = len(I) - CALL_HEAD
    nq, nplan = I[h + _NQ], I[h + _NPLAN]
    return (c_view(F, I[h + _WORK], (I[h + _EDATA] - I[h + _WORK],)), c_view(F, I[h + _EDATA], (2 * nq + nplan,)),
            c_view(F, I[h + _QAB], (3, nq)), c_view(F, I[h + _QC], (nq,)), c_view(I, I[h + _PAIRS], (I[h + _NPAIRS],)),
            c_view(I, I[h + _STATE], (1,)), c_view(I, I[h + _PLANNED], (nplan,)), I[h + _PACKET])


@njit(cache=True)
def edge_call(F, I, a, b, resolution, mode, first, stop, steps):
    """:func:`edge_open` on a checker's call data (:func:`call_data`): ALL_FREE; p >= 0, the first position left
    open (its code and open pairs in the pairs block); or -2 - p where the step at position p is proven colliding."""
    work, edata, qab, qc, pairs, state, planned, packet = _call_views(F, I)
    if len(a) != len(planned) or len(b) != len(planned):
        raise ValueError("an edge's ends must have one value per planned coordinate")
    p = edge_open(F, I, work, pairs, state, qab, planned, edata, packet, a, b, resolution, mode, first, stop, steps)
    return -2 - p if p >= 0 and pairs[-1] == COLLIDES else p


@njit(cache=True)
def config_call(F, I, q, shift):
    """:func:`lazyground.drake.sphere_kernels.certify_one` (its row test inlined) of planned coordinates ``q``
    (their plant positions written to F's configuration block, :func:`call_data`), on a checker's call data."""
    work, edata, qab, qc, pairs, state, planned, packet = _call_views(F, I)
    if len(q) != len(planned):
        raise ValueError("a configuration must have one value per planned coordinate")
    for j in range(len(qc)):
        qc[j] = edata[j]
    for i in range(len(planned)):
        qc[planned[i]] = q[i]
    return row_inline(qc, F, I, work, pairs, len(pairs) - 1, shift)


def edge_data(q_full: np.ndarray, weights: np.ndarray, wrap: np.ndarray) -> np.ndarray:
    """:func:`edge_open`'s ``edata``: start positions, weights over the plant's positions, wrap per planned one."""
    return np.concatenate([np.asarray(q_full, float), np.asarray(weights, float), np.asarray(wrap, float)])
