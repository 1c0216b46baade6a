"""The exact rest-to-rest timing of a straight line (lazyground.motion.trajectory, no Drake)."""

import numpy as np
import pytest

from lazyground.motion.trajectory import Limits, _sample, _time_line

LIMITS = Limits(np.array([1.0, 0.5, 2.0]), np.array([2.0, 1.0, 4.0]))


@pytest.mark.parametrize("d, duration, peak", [
    ([3.0, 1.0, 0.0], 3.5, 1.0),  # the line's speed is 1/3 (coordinate 0), its acceleration 2/3: 3 + 0.5 s
    ([0.1, 0.02, 0.0], 2.0 / np.sqrt(20.0), 0.1 * np.sqrt(20.0)),  # a triangle: s'' = 20 never reaches s' = 10
    ([0.0, -0.3, 0.0], 1.1, 1.0),  # coordinate 1 alone: 0.3 / 0.5 + 0.5 / 1
])
def test_a_line_takes_the_trapezoid_time_within_the_limits_from_rest_to_rest(d, duration, peak):
    a = np.array([0.5, -1.0, 2.0])
    line = _time_line(a, a + np.array(d), LIMITS)
    assert line.duration == pytest.approx(duration, rel=1e-12)
    t, q, qd, qdd = _sample([line], 0.001)
    assert np.allclose(q[0], a) and np.allclose(q[-1], a + np.array(d), atol=1e-12)
    assert np.allclose(qd[[0, -1]], 0.0, atol=1e-12)
    assert np.max(np.abs(qd) / LIMITS.velocity) == pytest.approx(peak, rel=1e-2)  # the sample nearest the peak
    assert np.max(np.abs(qd) / LIMITS.velocity) <= 1.0 + 1e-12
    assert np.max(np.abs(qdd) / LIMITS.acceleration) == pytest.approx(1.0)  # the acceleration limit binds
    # the positions are the integral of the velocities (trapezoid rule between samples)
    assert np.max(np.abs(np.diff(q, axis=0) - (qd[1:] + qd[:-1]) / 2 * np.diff(t)[:, None])) < 1e-6
    # every sample lies on the line, in order
    s = (q - a) @ np.array(d) / np.dot(d, d)
    assert np.allclose(q, a + s[:, None] * np.array(d)) and np.all(np.diff(s) >= 0)


def test_a_slowed_line_takes_longer_by_the_factor_and_moves_slower():
    line = _time_line(np.zeros(3), np.array([3.0, 1.0, 0.0]), LIMITS)
    slow = type(line)(line.a, line.d, line.V, line.A, stretch=2.0)
    assert slow.duration == pytest.approx(2 * line.duration)
    _, q, qd, qdd = _sample([slow], 0.001)
    assert np.allclose(q[-1], [3.0, 1.0, 0.0]) and np.max(np.abs(qd[:, 0])) == pytest.approx(0.5)
    assert np.max(np.abs(qdd[:, 0])) == pytest.approx(2.0 / 3.0 * 3.0 / 4.0)
