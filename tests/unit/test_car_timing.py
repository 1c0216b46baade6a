"""A car's path timed as driven (lazyground.motion.car_drive, car_timing; issue #16)."""

import re

import numpy as np
import pytest
from scipy.spatial import cKDTree

from lazyground.motion.car_drive import GRID, drives
from lazyground.motion.car_timing import WINDOWS, time_drive
from lazyground.motion.curve import unwrap_path
from lazyground.motion.trajectory import Limits, TimingSettings, _sample, time_path
from lazyground.motion.validate import trajectory_problems
from lazyground.planning.kinematics import make_space
from tests.unit.test_car import BASE, OFFSET, R
from tests.unit.toy import BoxWorld

CAR = make_space(BASE, "reeds-shepp", R, OFFSET)
LIMITS = Limits(np.array([1.5, 1.5, 0.5]), np.array([1.0, 1.0, 1.0]))  # the bundled car's
# a lane change and a turn, forwards: straights and arcs of both signs, curvature jumping between them
LANE_WAYPOINTS = np.array([[2.0, 2.0, 0.0], [12.0, 6.0, 0.0], [20.0, 12.0, 1.2]])
# a three-point turn: reverse gears in between (cusps)
TURN_WAYPOINTS = np.array([[10.0, 10.0, 0.0], [14.0, 12.0, 2.0], [12.0, 9.0, 3.1]])
LANE, TURN = CAR.dense_path(LANE_WAYPOINTS), CAR.dense_path(TURN_WAYPOINTS)
WAYPOINTS = {id(LANE): LANE_WAYPOINTS, id(TURN): TURN_WAYPOINTS}


def _planned_curve(path):
    """The planned curves at 1 mm (from the waypoints: between two samples of a straight the curve solver
    may return a tiny loop of the same length)."""
    return cKDTree(CAR.dense_path(WAYPOINTS[id(path)], 0.001)[:, :2])


def _rear_axle_slip(q, qd):
    """|lateral| / |speed| of the rear axle at each sample moving faster than 5 cm/s (0: no slip)."""
    c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
    vx, vy = qd[:, 0] - OFFSET * s * qd[:, 2], qd[:, 1] + OFFSET * c * qd[:, 2]  # the rear axle's velocity
    speed = np.hypot(vx, vy)
    moving = speed > 0.05
    return np.abs(-s * vx + c * vy)[moving] / speed[moving]


@pytest.mark.parametrize("path", [LANE, TURN], ids=["lane", "turn"])
def test_exact_curves_pass_through_every_planned_sample(path):
    for a, b in zip([0, *CAR.cusp_indices(path)], [*CAR.cusp_indices(path), len(path) - 1]):
        q = unwrap_path(CAR, path[a : b + 1])
        curves = drives(CAR, q, 0.0)
        assert len(curves) >= 2  # one per stretch of constant curvature
        ends = np.array([c.derivatives(np.array([c.length]))[0][0] for c in curves])
        # each stretch ends on a planned sample, the last on the segment's end
        assert all(np.min(np.linalg.norm(q - e, axis=1)) < 1e-9 for e in ends)
        assert np.allclose(ends[-1], q[-1], atol=1e-9)


@pytest.mark.parametrize("window", [2.0, 1.0, 0.5])
def test_averaged_curvature_is_continuous_within_the_radius_and_ends_on_the_plan(window):
    q = unwrap_path(CAR, LANE)
    (drive,) = drives(CAR, q, window)
    start, end = drive.derivatives(np.array([0.0, drive.length]))[0]
    assert np.allclose(start, q[0], atol=1e-9) and np.allclose(end, q[-1], atol=1e-8)
    assert np.max(np.abs(drive.kappa)) * R <= 1.0 + 1e-9
    # the planned curvature jumps by up to 2 / R; averaged over the window it ramps at most that much per
    # window, the end correction adding a little (12 % here at 2 m)
    slope = np.abs(np.diff(drive.kappa)) / np.diff(drive.s)
    assert np.max(slope) <= 2.0 / (R * window) * 1.25
    assert np.max(np.diff(drive.s)) <= GRID
    # it cuts the corners of the lane change by centimetres per metre of window (14 cm at 1 m here)
    gap, _ = _planned_curve(LANE).query(drive.derivatives(drive.s)[0][:, :2])
    assert 0.01 * window < np.max(gap) < 0.16 * window


def test_a_straight_line_takes_the_trapezoid_time():
    """Along x only the x limits bind: 1.5 m/s and 1 m/s^2 give 10 / 1.5 + 1.5 s for 10 m."""
    q = unwrap_path(CAR, CAR.dense_path(np.array([[5.0, 5.0, 0.0], [15.0, 5.0, 0.0]])))
    (drive,) = drives(CAR, q, 2.0)
    timed = time_drive(drive, LIMITS)
    assert timed.duration == pytest.approx(10.0 / 1.5 + 1.5, rel=0.01)


@pytest.mark.parametrize("path", [LANE, TURN], ids=["lane", "turn"])
@pytest.mark.parametrize("level", [0, 3])  # averaged over 2 m, the exact curves
def test_timed_drives_respect_the_limits_rest_at_their_ends_and_never_slide(path, level):
    parts = []
    for a, b in zip([0, *CAR.cusp_indices(path)], [*CAR.cusp_indices(path), len(path) - 1]):
        parts += [time_drive(d, LIMITS) for d in drives(CAR, unwrap_path(CAR, path[a : b + 1]), WINDOWS[level])]
    t, q, qd, qdd = _sample(parts, 0.0025)
    # the limits hold at the timing's nodes; between them (sampled 10x finer here) within a few percent,
    # which the uniform slow-down of the sampled output (test below) takes back
    assert np.max(np.abs(qd) / LIMITS.velocity) <= 1.01 and np.max(np.abs(qdd) / LIMITS.acceleration) <= 1.03
    assert np.max(np.abs(qd) / LIMITS.velocity) >= 0.95  # and some limit is reached: not slowed for nothing
    assert np.allclose(qd[[0, -1]], 0.0, atol=1e-9)
    assert np.max(_rear_axle_slip(q, qd)) < 1e-6
    # velocities are the derivative of the positions (no jump hidden between the samples)
    assert np.max(np.abs(np.diff(q, axis=0) / np.diff(t)[:, None] - 0.5 * (qd[1:] + qd[:-1]))) < 0.01


def _all_exact(label):
    """Whether a car trajectory's label says every stretch keeps its planned curve (e.g. "exact curves x3")."""
    return all(re.fullmatch(r"exact curves( x\d+)?", part) for part in label.split(" + "))


class NearThePlan(BoxWorld):
    """Free only within 2 mm of the planned curves: the averaged curve collides, the exact one does not."""

    def __init__(self, path):
        super().__init__([])
        self.tree = _planned_curve(path)

    def configs_free(self, qs):
        return self.tree.query(np.atleast_2d(qs)[:, :2])[0] < 2e-3


@pytest.mark.parametrize("path", [LANE, TURN], ids=["lane", "turn"])
def test_the_output_is_valid_and_a_colliding_average_gives_way_to_the_exact_curves(path):
    """(Two of the turn's gear segments are arcs of the smallest radius, steering from full left to full
    right: no correction of their averaged curvature stays within the radius, so they keep the exact curves.)"""
    stops = CAR.cusp_indices(path)
    free = BoxWorld([])
    traj = time_path(BASE, free, path, LIMITS, 0.01, stops=stops, car=CAR)
    assert trajectory_problems(traj, BASE, free, path[0], path[-1], 0.01) == []
    assert max(traj.peak_ratios) <= 1.001  # the samples within the limits (slowed uniformly if need be)
    assert np.max(_rear_axle_slip(traj.q, traj.qd)) < 1e-6
    assert not _all_exact(traj.curve)
    tight = NearThePlan(path)
    exact = time_path(BASE, tight, path, LIMITS, 0.01, stops=stops, car=CAR)
    assert trajectory_problems(exact, BASE, tight, path[0], path[-1], 0.01) == []
    assert _all_exact(exact.curve)
    assert traj.duration < exact.duration  # stopping at every curvature jump costs time


def test_half_speed_takes_twice_as_long():
    free = BoxWorld([])
    full = time_path(BASE, free, LANE, LIMITS, 0.01, car=CAR)
    half = time_path(BASE, free, LANE, LIMITS, 0.01, TimingSettings(speed=0.5), car=CAR)
    assert half.duration == pytest.approx(2.0 * full.duration, rel=0.01) and half.curve == full.curve


@pytest.mark.parametrize("seed", range(5))
def test_a_curves_derivative_splines_are_scipys(seed):
    """Curve builds its derivatives with scipy's formula, skipping scipy's checks (#31): the same coefficients,
    knots and values as ``BSpline.derivative``."""
    from scipy.interpolate import BSpline

    from lazyground.motion.curve import blended_curve

    rng = np.random.default_rng(seed)
    curve = blended_curve(np.cumsum(rng.uniform(-1.0, 1.0, (2 + seed, 4)), axis=0), 0.2)
    whole = BSpline(curve.knots, curve.control, 3)
    u = np.linspace(0.0, 1.0, 301)
    for nu in (0, 1, 2):
        ours, scipys = curve.spline(nu), whole.derivative(nu) if nu else whole
        assert ours.k == scipys.k and np.array_equal(ours.t, scipys.t) and np.array_equal(ours.c, scipys.c)
        assert np.array_equal(ours(u), scipys(u))


def test_sampling_plays_each_part_on_its_own_times():
    """_sample: parts one after another, a part too short for a sample of its own skipped, the end sampled."""
    from lazyground.motion.trajectory import _Rest, _time_line

    limits = Limits(np.array([1.0, 2.0]), np.array([1.0, 1.0]))
    a, b, c = np.zeros(2), np.array([1.0, 0.5]), np.array([1.0, 0.5 + 1e-9])
    parts = [_time_line(a, b, limits), _time_line(b, c, limits), _Rest(c, 0.25)]
    t, q, qd, qdd = _sample(parts, 0.01)
    assert t[-1] == pytest.approx(sum(p.duration for p in parts)) and np.all(np.diff(t) > 0)
    assert len(q) == len(qd) == len(qdd) == len(t)
    line = parts[0]
    inside = t < line.duration
    assert np.allclose(q[inside], line.evaluate(t[inside])[0])
    assert np.allclose(q[-1], c) and np.allclose(qd[-1], 0.0)
