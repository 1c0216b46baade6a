"""The compiled sweep's bounds (sphere_kernels.sweep_rows): rows proven free from an anchor's clearance are free.

Planted bugs 2k and 7k of docs/reliability.md: the bundled scenes' sweeps pass with either (the lever sum
overestimates there), so these tests pin the two bounds down by hand."""

import numpy as np
import pytest

from lazyground.drake import sphere_kernels as kernels


@pytest.mark.parametrize("a", [1e-3, 0.3, 0.65, 2.0])
def test_the_moved_bound_is_at_least_the_true_one(a):
    """A point at lever sum a moves at most a (e^s - 1) / s on the straight line while the revolute joints turn by
    s in total (the argument of SphereCertifier.levers); the kernels' bound may not be below that anywhere in
    (0, 1]. (A row's endpoint moves at most a itself, docs/reliability.md: this holds the bound to its documented
    argument, no sweep can show the difference.)"""
    for s in np.linspace(1e-4, 1.0, 2001):
        assert kernels.moved_bound(a, s) >= a * np.expm1(s) / s
    # and not far above it: the bound is a (1 + s) plus rounding (2 at s = 1, the true 1.718...)
    assert kernels.moved_bound(a, 1.0) == pytest.approx(2.0 * a)


# two arms on separate revolute joints (axes: world z) at x = -D and x = +D, each of length L pointing along +y
# with a sphere of radius R at its tip; the tips are a self pair (threshold 0), the one obstacle is far away and
# not checked. At q = (-t, t) the tips lean toward each other: they are 2 D - 2 L sin t apart.
D, L, R = 0.11, 0.6, 0.05
_TWO_ARMS = dict(
    counts=dict(m=2, n=2, G=2, S=2, O=1, P=1, I=2),
    K=np.array([[[1, 0, 0, -D], [0, 1, 0, 0], [0, 0, 1, 0]], [[1, 0, 0, D], [0, 1, 0, 0], [0, 0, 1, 0]]], float),
    F=np.array([np.eye(4)[:3]] * 2), parent=[0, 0], kinds=[0, 0], index=[0, 1], slot=[1, 2], node=[0, 1],
    gR=np.array([np.eye(3)] * 2), go=[[0, L, 0]] * 2, ghalf=np.zeros((2, 3)), ground=[R, R], grad=[R, R],
    gcyl=[0, 0], gexact=[1, 1],
    sc=[[0, L, 0]] * 2, sr=[R, R], start=[0, 1, 2], ic=[[0, L, 0]] * 2, ir=[R, R], istart=[0, 1, 2], below=[2e-4],
    oR=np.eye(3), oo=[10.0, 0.0, 0.0], ohalf=[0.1] * 3, oround=[0.0], ac=[10.0, 0.0, 0.0], ah=[0.1] * 3,
    env=[[0.01], [0.01]], reach2=[[-1.0], [-1.0]], ocyl=[0], oexact=[1],
    self_thr=[0.0], mover=[0], other=[1])


def _sweep(Q):
    fd, idata = kernels.pack(_TWO_ARMS)
    work = np.zeros(kernels.work_size(idata))
    pairs = np.zeros((len(Q), 8), np.int64)
    above = np.eye(2, dtype=np.int64)  # joint j moves only geometry j
    return (kernels.sweep_rows(Q, fd, idata, work, above, pairs),
            kernels.certify_rows(Q, fd, idata, work, pairs))


def test_a_pair_closing_from_both_sides_is_not_proven_free_from_the_anchor():
    """Each tip moves less than ROOM, both together more than their clearance: at the anchor q = 0 the tips'
    spheres are 2 D - 2 R = 0.12 m apart (the pair's clearance: ROOM), at t = 0.11 each tip's bound is
    0.11 * (L + R) * (1 + 0.22) = 0.087 m < ROOM (both stay within their environment clearance, ROOM), but
    the spheres are then 0.22 - 2 * 0.6 * sin(0.11) = 0.088 m apart, overlapping by 12 mm."""
    t = np.linspace(0.0, 0.11, 12)
    Q = np.column_stack([-t, t])
    code, whole = _sweep(Q)
    free = 2 * D - 2 * L * np.sin(t) > 2 * R  # worked out by hand
    assert free[0] and not free[-1]
    assert kernels.moved_bound(0.11 * (L + R), 0.22) < kernels.ROOM  # each tip alone stays covered
    assert np.all(whole[~free] == kernels.COLLIDES)  # the whole test sees the overlap (an inner sphere reaches in)
    assert np.all(code[~free] != 0)  # the sweep may not prove them free from the anchor
    assert np.all(code[~free] == whole[~free])
    assert code[0] == 0  # the anchor itself is free
