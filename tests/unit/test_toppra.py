"""TOPP-RA in numpy (lazyground.motion.toppra, no Drake); tests/drake/test_toppra_drake.py compares it with Drake's."""

import numpy as np
import pytest

from lazyground.motion.curve import blended_curve
from lazyground.motion.toppra import toppra
from lazyground.motion.trajectory import Limits, _time_line

LIMITS = Limits(np.array([1.0, 0.5, 2.0]), np.array([2.0, 1.0, 4.0]))


@pytest.mark.parametrize("d", [[3.0, 1.0, 0.0], [0.1, 0.02, 0.0], [0.0, -0.3, 0.0]])
def test_a_line_takes_about_the_exact_trapezoid_time_never_less(d):
    # the switches between speeding up, cruising and braking fall on grid points: a finer grid comes closer
    a, d = np.array([0.5, -1.0, 2.0]), np.array(d)
    exact = _time_line(a, a + d, LIMITS).duration
    for n, within in ((9, 0.1), (1001, 1e-3)):
        grid = np.linspace(0.0, 1.0, n)
        ones = np.ones((n, 1))
        timing = toppra(ones * d, 0.0 * ones * d, grid, LIMITS.velocity, LIMITS.acceleration)
        assert exact * (1 - 1e-9) <= timing.end_time() <= exact * (1 + within)
        assert timing.sd[0] == timing.sd[-1] == 0.0


def test_a_curve_keeps_the_limits_at_the_grid_points_from_rest_to_rest():
    path = np.array([[0.0, 0.0, 0.0], [1.0, 0.5, -0.5], [1.5, -0.5, 0.0], [2.0, 0.0, 1.0]])
    curve = blended_curve(path, 0.2)
    grid = curve.grid(3)
    d1, d2 = curve.spline(1)(grid), curve.spline(2)(grid)
    timing = toppra(d1, d2, grid, LIMITS.velocity, LIMITS.acceleration)
    assert np.all(np.diff(timing.t) > 0) and timing.sd[0] == timing.sd[-1] == 0.0
    s, sd, sdd = timing.evaluate(timing.t[:-1])
    assert np.allclose(s, grid[:-1]) and np.allclose(sd, timing.sd[:-1])
    assert np.allclose(timing.evaluate(timing.t[1:] - 1e-12)[0], grid[1:])  # s(t) runs through the grid
    assert np.all(np.abs(d1[:-1] * sd[:, None]) <= LIMITS.velocity * (1 + 1e-9))
    # the interpolation rows: the acceleration limits hold at both ends of every interval under its u
    for k in (0, 1):
        acc = d1[k : len(sdd) + k] * sdd[:, None] + d2[k : len(sdd) + k] * timing.sd[k : len(sdd) + k, None] ** 2
        assert np.all(np.abs(acc) <= LIMITS.acceleration * (1 + 1e-9))
    # and it is time-optimal: some limit binds in every interval (else it could go faster)
    ratios = np.maximum(np.max(np.abs(d1[:-1] * sd[:, None]) / LIMITS.velocity, axis=1),
                        np.max(np.abs(d1[:-1] * sdd[:, None] + d2[:-1] * sd[:, None] ** 2) / LIMITS.acceleration, axis=1))
    assert np.median(ratios) > 0.99
