"""TOPP-RA for joint limits in numpy (lazyground.motion.toppra, no Drake)."""

import numpy as np
import pytest

from lazyground.motion.curve import blended_curve
from lazyground.motion.toppra import toppra

V, A = np.array([1.0, 0.5, 2.0]), np.array([2.0, 1.0, 4.0])


def test_a_straight_line_takes_the_trapezoid_time():
    # q(s) = s d on [0, 1], d = (3, 1, 0): speed bound 1/3 (coordinate 0), acceleration 2/3: 3 + 0.5 s
    grid = np.linspace(0.0, 1.0, 201)
    d = np.array([3.0, 1.0, 0.0])
    timing = toppra(grid, np.tile(d, (len(grid), 1)), np.zeros((len(grid), 3)), V, A)
    # the switch from speeding up to cruising falls inside an interval (s'' is constant in each): a little slower
    assert 3.5 - 1e-9 <= timing.end_time() <= 3.5 * (1.0 + 1e-4)
    s, sd, sdd = timing.evaluate(np.linspace(0.0, timing.end_time(), 1001))
    assert s[0] == 0.0 and s[-1] == pytest.approx(1.0) and sd[0] == 0.0 and sd[-1] == pytest.approx(0.0, abs=1e-9)
    assert np.max(np.abs(sd) * 3.0) <= 1.0 + 1e-9 and np.max(np.abs(sdd) * 3.0) <= 2.0 + 1e-9
    assert np.all(np.diff(s) >= -1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_a_blended_curve_meets_the_limits_at_the_grid_points_and_stops_at_both_ends(seed):
    path = np.random.default_rng(seed).uniform(-2.0, 2.0, (5, 3))
    curve = blended_curve(path, 0.2)
    grid = curve.grid(4)
    dq, ddq = curve.spline(1)(grid), curve.spline(2)(grid)
    timing = toppra(grid, dq, ddq, V, A)
    sd, sdd = timing.sd, timing.sdd
    assert sd[0] == 0.0 and sd[-1] == 0.0 and np.all(sd[1:-1] > 0.0)
    assert np.all(np.abs(dq * sd[:, None]) <= V * (1.0 + 1e-9))
    # the acceleration at the start of each interval, with its constant s''
    qdd = dq[:-1] * sdd[:, None] + ddq[:-1] * sd[:-1, None] ** 2
    assert np.all(np.abs(qdd) <= A * (1.0 + 1e-9))
    # time optimal: at some grid point inside the path a limit binds (speed or acceleration)
    assert np.max(np.abs(qdd) / A) > 0.999 or np.max(np.abs(dq * sd[:, None]) / V) > 0.999


def test_a_curve_that_stops_inside_has_no_timing():
    grid = np.linspace(0.0, 1.0, 11)
    dq = np.ones((11, 3))
    dq[5] = 0.0  # q' = 0 at one grid point bounds neither speed nor acceleration there: the path is timed
    assert toppra(grid, dq, np.zeros((11, 3)), V, A) is not None
    assert toppra(np.array([0.0, 1.0]), np.zeros((2, 3)), np.zeros((2, 3)), V, A) is None
