"""The trajectory validator on hand-built trajectories (no planner, no Drake): every scene test relies on it,
so each of its checks is shown to fire, on either sign, and not to fire on a smooth motion at the limits."""

import numpy as np
import pytest

from lazyground.motion.limits import Limits
from lazyground.motion.trajectory import Trajectory
from lazyground.motion.validate import LIMIT_TOLERANCE, trajectory_problems
from tests.unit.toy import SPACE, BoxWorld

V_MAX, A_MAX = np.array([1.0, 2.0]), np.array([4.0, 3.0])
RES = 0.01


def rest_to_rest(start, goal, duration, n=401):
    """A minimum-jerk (quintic) motion: s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5, at rest at both ends.

    Peaks, worked out by hand: s' = 30 tau^2 (1 - tau)^2 is largest at tau = 1/2, 15/8 per unit of tau;
    s'' = 60 tau (1 - tau)(1 - 2 tau) is largest at tau = 1/2 -/+ sqrt(3)/6, 10 sqrt(3)/3 per unit of tau^2.
    """
    t = np.linspace(0.0, duration, n)
    tau = t / duration
    d = np.asarray(goal, float) - start
    s = 10 * tau**3 - 15 * tau**4 + 6 * tau**5
    sd = (30 * tau**2 - 60 * tau**3 + 30 * tau**4) / duration
    sdd = (60 * tau - 180 * tau**2 + 120 * tau**3) / duration**2
    return t, start + s[:, None] * d, sd[:, None] * d, sdd[:, None] * d


def traj(t, q, qd, qdd):
    return Trajectory(("x", "y"), (False, False), t, q, qd, qdd, Limits(V_MAX, A_MAX), "test")


def problems(tr, world=None, start=None, goal=None):
    world = world or BoxWorld([])
    start = tr.q[0] if start is None else start
    goal = tr.q[-1] if goal is None else goal
    return trajectory_problems(tr, SPACE, world, start, goal, RES)


START, GOAL = np.array([1.0, 1.0]), np.array([4.0, 2.0])


def fastest_duration():
    """The shortest duration of the quintic from START to GOAL within V_MAX and A_MAX (by hand, from the peaks)."""
    d = np.abs(GOAL - START)
    return float(max(np.max(15 / 8 * d / V_MAX), np.sqrt(np.max(10 * np.sqrt(3) / 3 * d / A_MAX))))


def test_a_smooth_motion_at_the_limits_passes():
    """The quintic timed to touch its binding limit (x velocity: 15/8 * 3 m / 1 m/s = 5.625 s) has no problem."""
    T = fastest_duration()
    assert T == pytest.approx(5.625)
    tr = traj(*rest_to_rest(START, GOAL, T))
    assert tr.peak_ratios[0] == pytest.approx(1.0, abs=1e-4)
    assert problems(tr) == []


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_velocity_overshoot_is_found_on_either_sign(sign):
    """Timed 10 % faster than its limit allows, the motion is reported, moving forwards or backwards."""
    T = fastest_duration() / 1.1
    start, goal = (START, GOAL) if sign > 0 else (GOAL, START)
    tr = traj(*rest_to_rest(start, goal, T))
    assert np.sign(tr.qd[:, 0]).sum() * sign > 0  # the x velocity has the sign asked for
    assert problems(tr) == ["trajectory exceeds a velocity limit 1.100x"]


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_an_acceleration_overshoot_is_found_on_either_sign(sign):
    """A quintic over 0.5 m in 1.2 s is slow enough (peak 0.625 m/s) but accelerates at 10 sqrt(3)/3 * 0.5 / 1.44
    = 2.005 m/s^2 in y, above a 1.5 m/s^2 limit: 1.337x."""
    start = np.array([5.0, 5.0])
    goal = start + sign * np.array([0.0, 0.5])
    t, q, qd, qdd = rest_to_rest(start, goal, 1.2, n=2001)
    tr = Trajectory(("x", "y"), (False, False), t, q, qd, qdd, Limits(V_MAX, np.array([4.0, 1.5])), "test")
    want = 10 * np.sqrt(3) / 3 * 0.5 / 1.44 / 1.5
    assert want == pytest.approx(1.3365, abs=1e-4)
    assert problems(tr) == [f"trajectory exceeds a acceleration limit {want:.3f}x"]


def test_the_limit_tolerance_is_one_percent_and_no_more():
    base = fastest_duration()
    assert problems(traj(*rest_to_rest(START, GOAL, base / (1 + LIMIT_TOLERANCE / 2)))) == []
    assert problems(traj(*rest_to_rest(START, GOAL, base / (1 + 2 * LIMIT_TOLERANCE)))) == [
        "trajectory exceeds a velocity limit 1.020x"]


def test_ends_times_and_rest_are_checked():
    t, q, qd, qdd = rest_to_rest(START, GOAL, 6.0)
    tr = traj(t, q, qd, qdd)
    assert problems(tr, start=START + [0.0, 1e-3]) == ["trajectory does not start at the start configuration"]
    assert problems(tr, goal=GOAL + [1e-3, 0.0]) == ["trajectory does not end at the goal configuration"]
    t2 = t.copy()
    t2[200] = t2[199]
    assert problems(traj(t2, q, qd, qdd)) == ["trajectory times do not increase"]
    qd2 = qd.copy()
    qd2[-1] = [0.01, 0.0]
    assert problems(traj(t, q, qd2, qdd)) == ["trajectory does not start and end at rest"]
    qd2 = qd.copy()
    qd2[0] = [0.0, -0.01]
    assert problems(traj(t, q, qd2, qdd)) == ["trajectory does not start and end at rest"]


def test_a_wall_between_two_samples_is_found_on_the_join():
    """Samples 0.5 m apart straddle a 0.05 m wall at x = 2.5: no sample touches it, the join does."""
    t = np.linspace(0.0, 4.0, 9)
    q = np.column_stack([np.linspace(0.75, 4.75, 9), np.full(9, 5.0)])
    assert not np.any((q[:, 0] >= 2.45) & (q[:, 0] <= 2.55))
    zero = np.zeros_like(q)
    tr = Trajectory(("x", "y"), (False, False), t, q, zero, zero, Limits(V_MAX, A_MAX), "test")
    wall = BoxWorld([(2.45, 0.0, 2.55, 10.0)])
    assert problems(tr, wall) == ["trajectory collides at resolution 0.01"]
    assert problems(tr, BoxWorld([(2.45, 6.0, 2.55, 10.0)])) == []


# --- written to kill surviving mutants (tools/mutation.py validate) -----------------------------------------------

def _still(q):
    zero = np.zeros_like(q)
    return Trajectory(("x", "y"), (False, False), np.linspace(0.0, 1.0, len(q)), q, zero, zero.copy(),
                      Limits(V_MAX, A_MAX), "test")


def test_a_limit_exactly_at_the_tolerance_passes():
    tr = _still(np.column_stack([np.linspace(1.0, 2.0, 5), np.full(5, 5.0)]))
    tr.qd[2] = [1.01 * V_MAX[0], 0.0]  # a ratio of exactly 1 + LIMIT_TOLERANCE
    assert problems(tr) == []
    tr.qd[2] = [1.0101 * V_MAX[0], 0.0]
    assert problems(tr) == ["trajectory exceeds a velocity limit 1.010x"]


def test_ends_and_rest_are_compared_within_a_micrometre():
    tr = _still(np.column_stack([np.linspace(1.0, 2.0, 5), np.full(5, 5.0)]))
    start, goal = tr.q[0].copy(), tr.q[-1].copy()
    assert problems(tr, start=start + [5e-7, 0.0], goal=goal - [0.0, 5e-7]) == []
    assert problems(tr, start=start + [2e-6, 0.0]) == ["trajectory does not start at the start configuration"]
    assert problems(tr, goal=goal - [0.0, 2e-6]) == ["trajectory does not end at the goal configuration"]
    tr.qd[-1] = [5e-7, 0.0]
    assert problems(tr) == []
    tr.qd[-1] = [2e-6, 0.0]
    assert problems(tr) == ["trajectory does not start and end at rest"]


def test_a_start_inside_an_obstacle_counts_unless_asked_to_skip_it():
    tr = _still(np.column_stack([np.linspace(1.0, 3.0, 9), np.full(9, 5.0)]))
    box = BoxWorld([(0.5, 4.5, 1.3, 5.5)])  # the first samples (a lift-off from a support) are inside
    assert problems(tr, box) == ["trajectory collides at resolution 0.01"]
    assert trajectory_problems(tr, SPACE, box, tr.q[0], tr.q[-1], RES, from_first_free=True) == []


@pytest.mark.parametrize("bad", [[1.0, 0.0], [1.0, -2.0], [np.inf, 1.0], [1.0, np.nan]])
def test_limits_are_positive_and_finite_floats(bad):
    with pytest.raises(ValueError, match="velocity limits must be positive and finite"):
        Limits(np.array(bad), A_MAX)
    with pytest.raises(ValueError, match="acceleration limits must be positive and finite"):
        Limits(V_MAX, np.array(bad))
    ok = Limits([1, 2], [3, 4])
    assert ok.velocity.dtype == float and ok.acceleration.dtype == float
