"""Time parameterisation on Drake: TOPP-RA over a smooth curve through a path.

Each piece of the path (pieces end where the robot must stop: the start of a straight
approach) gets a blended B-spline (:mod:`lazyground.motion.curve`). The sampled output is
checked densely at the fine resolution (its samples and the joins between them, the very
check ``lazyground.motion.validate`` re-runs); a piece whose curve collides is redone with
less blending, then as the piecewise-linear path with a stop at every waypoint. When even
that fails (the path grazes an obstacle between the points its own fine check tested)
there is no trajectory (:class:`MotionError`). Drake's ``Toppra`` (Pham and Pham, IEEE T-RO 2018) finds the fastest timing under
per-joint velocity and acceleration limits. TOPP-RA enforces its constraints at grid
points; the sampled trajectory is then slowed uniformly by the largest overshoot between
them, so every sample respects the limits. ``speed`` s scales the limits to s v_max and
s^2 a_max, i.e. the same motion played 1/s times slower.
"""

from __future__ import annotations

import contextlib
import functools
import logging
from dataclasses import dataclass, replace

import numpy as np

from lazyground.motion.car_timing import car_piece_timer
from lazyground.motion.curve import Curve, blended_curve, unwrap_path
from lazyground.motion.limits import Limits  # noqa: F401  (re-exported: callers time paths under Limits)
from lazyground.motion.validate import first_colliding_join
from lazyground.planning.stop import default_clock  # the split's clock (tests drive it)
from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace


@dataclass(frozen=True)
class TimingSettings:
    """``speed`` in (0, 1] scales the limits; samples every 1 / ``sample_rate`` s."""

    speed: float = 1.0
    sample_rate: float = 100.0  # Hz
    blends: tuple[float, ...] = (0.3, 0.1, 0.03)  # tried in order; then stops at waypoints
    grid_per_span: int = 4  # TOPP-RA grid points per knot span of the curve (retried with twice as many) ...
    corner_grid: int | None = None  # ... and per span that bends (None: as many)

    def for_shortened(self) -> "TimingSettings":
        """For a shortened path (few long segments, not a car's dense curve samples).

        On the Fetch scenes, blends of 0.2 / 0.07 / 0.02 and 3 grid points per span gave 6 %
        shorter trajectories than 0.3 / 0.1 / 0.03 and 4, with 30 % fewer corner configurations to
        check and 2/3 of the TOPP-RA time; on a car's paths (hundreds of short segments) they gave
        trajectories 1.3-2x longer, which keep the defaults. Then (#31) 4 grid points on the straight
        spans and 2 (their ends) on the spans that bend: the largest overshoot between grid points, which
        slows a whole curve down, lay on straight spans (the robot speeding up or cruising). On the 30
        curves of the three Fetch scenes, seeds 0-9, against 3 per span: 11-13 % fewer grid points (Toppra's
        solve is ~0.15 ms a point), durations 7.6 / 4.6 / 9.0 % shorter in sum on cans_1 / cans_2 / boxes_3
        (one curve in 30 6 % longer); 4 and 3 gave 1-2 % shorter durations for 25 % more points.
        """
        return replace(self, blends=(0.2, 0.07, 0.02), grid_per_span=4, corner_grid=2)

    def __post_init__(self):
        if not 0 < self.speed <= 1:
            raise ValueError(f"speed must be in (0, 1], got {self.speed}")
        if not self.sample_rate > 0:
            raise ValueError(f"sample_rate must be > 0, got {self.sample_rate}")


@dataclass(frozen=True)
class Trajectory:
    """A timed motion sampled at a fixed rate; ``q`` is unwrapped (continuous) in ``wrap`` coordinates."""

    joint_names: tuple[str, ...]
    wrap: tuple[bool, ...]
    t: np.ndarray  # (m,)
    q: np.ndarray  # (m, dim)
    qd: np.ndarray
    qdd: np.ndarray
    limits: Limits  # the limits it was timed under (already scaled by speed)
    curve: str  # how it was shaped, e.g. "blend 0.3" or "stops at waypoints", per piece joined by " + "
    time_s: float = 0.0  # computing it
    events: tuple[tuple[float, str], ...] = ()  # (t, what) while at rest, e.g. (4.2, "close gripper")

    @property
    def duration(self) -> float:
        return float(self.t[-1])

    @property
    def peak_ratios(self) -> tuple[float, float]:
        """The largest |qd| / v_max and |qdd| / a_max over the samples."""
        return float(np.max(np.abs(self.qd) / self.limits.velocity)), float(np.max(np.abs(self.qdd) / self.limits.acceleration))

    @property
    def limits_bind(self) -> bool:
        """Whether a velocity or acceleration limit is reached (within 1%) somewhere."""
        return max(self.peak_ratios) >= 0.99


def time_path(
    space: ConfigSpace,
    checker: ValidityChecker,
    path: np.ndarray,
    limits: Limits,
    fine_resolution: float,
    settings: TimingSettings = TimingSettings(),
    stops: tuple[int, ...] = (),
    car=None,
) -> Trajectory:
    """A timed trajectory through ``path`` (start to goal, resting at both).

    Args:
        space: the planner's configuration space.
        checker: its validity checker; every curve is checked at ``fine_resolution``.
        path: (n, dim) waypoints, valid at ``fine_resolution``.
        limits: per-coordinate velocity and acceleration limits (before ``speed``).
        fine_resolution: the spacing of the dense check of every curve.
        settings: speed, sample rate, blends.
        stops: waypoint indices where the robot stops (e.g. the start of a straight approach);
            the segment after a stop stays straight.
        car: the CarSpace of a car's dense path (``stops`` its gear changes): each gear segment
            is driven along its curves (:mod:`lazyground.motion.car_timing`), not blended.

    Returns:
        The Trajectory, sampled every ``1 / settings.sample_rate`` s and at its end.

    Raises:
        MotionError: every way of timing a piece collides (the path grazes an obstacle).
    """
    t0 = default_clock()
    q = unwrap_path(space, path)
    scaled = Limits(limits.velocity * settings.speed, limits.acceleration * settings.speed**2)
    pieces = split_at_stops(q, stops)
    if car is not None:
        time_piece, levels = car_piece_timer(car, pieces, scaled)
    else:
        options = [*settings.blends, None]  # None: stop at every waypoint
        levels = len(options)

        def time_piece(k: int, level: int):
            return _time_piece(space, pieces[k], options[level], fine_resolution, scaled, 1.0 / settings.sample_rate,
                               (settings.grid_per_span, settings.corner_grid or settings.grid_per_span))

    return assemble(space, checker, q[0], len(pieces), levels, time_piece, scaled, fine_resolution,
                    settings.sample_rate, t0)


def split_at_stops(q: np.ndarray, stops: tuple[int, ...]) -> list[np.ndarray]:
    """The pieces of a path between the waypoints where it stops (and its ends)."""
    cuts = sorted({0, len(q) - 1, *(k for k in stops if 0 < k < len(q) - 1)})
    return [q[a : b + 1] for a, b in zip(cuts[:-1], cuts[1:])]


def assemble(space: ConfigSpace, checker: ValidityChecker, q0: np.ndarray, n_pieces: int, n_levels: int,
             time_piece, limits: Limits, fine_resolution: float, sample_rate: float, t0: float) -> Trajectory:
    """The timed pieces played one after another, sampled, within the limits and checked densely.

    ``time_piece(k, level)`` gives piece k's ([timed parts], label) at a level of caution (0 first);
    the piece playing where the sampled motion collides is redone at the next level.

    Raises:
        MotionError: a piece collides at its last level.
    """
    dt = 1.0 / sample_rate
    level = [0] * n_pieces
    timed = [time_piece(k, 0) for k in range(n_pieces)]
    slowdowns = 0
    while True:
        parts = [part for piece in timed for part in piece[0]] or [_Rest(q0)]
        # all of the curve is checked, its straight spans too: a check that skipped them (they lie on
        # fine-checked segments) let a grazing path through a re-check that tests other points of them
        t, qs, qd, qdd = _sample(parts, dt)
        slower = _over_limits(qd, qdd, limits)
        if slower > 1.0 and slowdowns < MAX_SLOWDOWNS:
            # a peak between the probes of the timing shows in the output samples: every part is slowed
            # by it, and the new samples are checked again (they lie elsewhere on the same curves)
            slowdowns += 1
            timed = [([_slowed(part, slower) for part in curves], label) for curves, label in timed]
            continue
        bad = first_colliding_join(space, checker, qs, fine_resolution, along=True)
        if bad is None:
            break
        # the piece playing at the colliding join is redone more cautiously; the whole output is checked
        # again (rarely needed), so that it passes the very check a re-check runs
        ends = np.cumsum([sum(part.duration for part in piece[0]) for piece in timed])
        k = min(int(np.searchsorted(ends, t[bad], side="right")), n_pieces - 1)
        level[k] += 1
        if level[k] >= n_levels:
            raise MotionError(f"no collision-free timing: the path grazes an obstacle between its fine-resolution "
                              f"checks near t = {t[bad]:.2f} s")
        timed[k] = time_piece(k, level[k])
    labels = " + ".join(piece[1] for piece in timed)
    return Trajectory(space.names, tuple(bool(w) for w in space.wrap), t, qs, qd, qdd, limits, labels,
                      default_clock() - t0)


MAX_SLOWDOWNS = 3  # uniform slow-downs of a timed path whose output samples still exceed a limit


def _over_limits(qd: np.ndarray, qdd: np.ndarray, limits: Limits) -> float:
    """The uniform slow-down factor (> 1) that brings sampled velocities and accelerations within the limits, else 1."""
    need = max(float(np.max(np.abs(qd) / limits.velocity, initial=0.0)),
               float(np.sqrt(np.max(np.abs(qdd) / limits.acceleration, initial=0.0))))
    return need * (1.0 + 1e-6) if need > 1.0 else 1.0


def _slowed(part, factor: float):
    """A timed part played ``factor`` times slower (a rest, which has no ``stretch``, stays a rest)."""
    return replace(part, stretch=part.stretch * factor) if hasattr(part, "stretch") else part


class MotionError(RuntimeError):
    """No valid timed trajectory could be made (the caller reports it; the path stays valid)."""


@dataclass(frozen=True)
class _TimedLine:
    """The fastest rest-to-rest motion along the straight line a -> a + d, played ``stretch`` times slower.

    Along a line every coordinate moves in proportion, q = a + s d, so the limits bound s' by
    V = min v_j / |d_j| and s'' by A = min a_j / |d_j|: the time-optimal s(t) accelerates at A, cruises
    at V (when it reaches it) and brakes at A, exactly (no grid to refine, no overshoot to slow down);
    TOPP-RA found the same timing (within its grid) at ~2 ms per line.
    """

    a: np.ndarray
    d: np.ndarray
    V: float
    A: float
    stretch: float = 1.0

    @property
    def _ramp(self) -> float:
        """Seconds of speeding up (and of slowing down)."""
        return min(self.V / self.A, 1.0 / np.sqrt(self.A))

    @property
    def duration(self) -> float:
        ramp = self._ramp
        return (2.0 * ramp + (1.0 - self.A * ramp**2) / self.V) * self.stretch

    def evaluate(self, t: np.ndarray):
        """q, qd, qdd at times t in [0, duration]."""
        ramp, total = self._ramp, self.duration / self.stretch
        tau = np.clip(np.asarray(t, float) / self.stretch, 0.0, total)
        top = self.A * ramp  # the cruising speed (V, or the peak of a triangle)
        up, down = tau < ramp, tau > total - ramp
        left = total - tau
        s = np.where(up, 0.5 * self.A * tau**2,
                     np.where(down, 1.0 - 0.5 * self.A * left**2, 0.5 * self.A * ramp**2 + top * (tau - ramp)))
        sd = np.where(up, self.A * tau, np.where(down, self.A * left, top)) / self.stretch
        sdd = np.where(up, self.A, np.where(down, -self.A, 0.0)) / self.stretch**2
        return self.a + s[:, None] * self.d, sd[:, None] * self.d, sdd[:, None] * self.d


def _time_line(a: np.ndarray, b: np.ndarray, limits: Limits) -> _TimedLine:
    d = b - a
    moving = np.abs(d) > 0
    V = float(np.min(limits.velocity[moving] / np.abs(d[moving])))
    A = float(np.min(limits.acceleration[moving] / np.abs(d[moving])))
    return _TimedLine(a, d, V, A)


def _time_piece(space, piece: np.ndarray, blend: float | None, resolution: float, limits: Limits, dt: float,
                grid: tuple[int, int]):
    """([timed curves], label) for a piece between two stops: one blended curve, or (``blend`` None,
    or TOPP-RA failing on the curve) straight segments with a stop at every waypoint."""
    if len(piece) == 2 or blend is None:
        label = "straight" if len(piece) == 2 else "stops at waypoints"
        return [_time_line(a, b, limits) for a, b in zip(piece[:-1], piece[1:]) if np.any(a != b)], label
    keep = _merge_close(space, piece, resolution)
    try:
        return [_time_curve(blended_curve(piece[keep], blend), limits, dt, grid)], f"blend {blend:g}"
    except RuntimeError:  # TOPP-RA failed on this curve (numerics): stops at waypoints
        return _time_piece(space, piece, None, resolution, limits, dt, grid)


def _merge_close(space: ConfigSpace, piece: np.ndarray, resolution: float) -> np.ndarray:
    """The indices of the waypoints kept when dropping interior ones closer than ``resolution``
    to the previous kept one.

    Near-duplicate waypoints make corners with near-zero dq/du; the curve is checked
    densely anyway, so dropping them only changes which curve is checked.
    """
    keep = [0]
    for k in range(1, len(piece) - 1):
        if space.distance(piece[keep[-1]], piece[k]) >= resolution:
            keep.append(k)
    if len(keep) > 1 and space.distance(piece[keep[-1]], piece[-1]) < resolution:
        keep.pop()
    return np.array(keep + [len(piece) - 1])


@dataclass(frozen=True)
class _Quadratics:
    """Drake's s(t) from TOPP-RA (quadratic pieces: constant s'' between grid points) as arrays, so that
    s, s', s'' at many times take a few numpy calls, not new PiecewisePolynomial derivatives per
    evaluation; the same values as the PiecewisePolynomial's (to rounding)."""

    breaks: np.ndarray  # (n + 1,) segment times
    s: np.ndarray  # (n,) at each segment's start
    sd: np.ndarray
    sdd: np.ndarray  # constant on each segment

    @classmethod
    def of(cls, pp) -> "_Quadratics":
        n = pp.get_number_of_segments()
        if any(pp.getSegmentPolynomialDegree(k) > 2 for k in range(n)):
            raise ValueError("s(t) has a piece of degree > 2")
        breaks = np.asarray(pp.get_segment_times(), float)
        start, mid = breaks[:-1], 0.5 * (breaks[:-1] + breaks[1:])
        sdd = pp.derivative(2).vector_values(mid)[0]
        return cls(breaks, pp.vector_values(start)[0], pp.derivative(1).vector_values(mid)[0] - sdd * (mid - start), sdd)

    @property
    def end_time(self) -> float:
        return float(self.breaks[-1])

    def __call__(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """s, s', s'' at times tau in [0, end_time]."""
        k = np.clip(np.searchsorted(self.breaks, tau, side="right") - 1, 0, len(self.sdd) - 1)
        h = tau - self.breaks[k]
        sd, sdd = self.sd[k], self.sdd[k]
        return self.s[k] + h * (sd + 0.5 * h * sdd), sd + h * sdd, sdd


@dataclass(frozen=True)
class _Timed:
    """One curve q(u) timed by u(t) on [0, duration]; ``stretch`` >= 1 slows u(t) uniformly."""

    curve: Curve
    s_of_t: _Quadratics  # u(t): Drake's TOPP-RA solution
    stretch: float

    @property
    def duration(self) -> float:
        return self.s_of_t.end_time * self.stretch

    def evaluate(self, t: np.ndarray, positions: bool = True):
        """q, qd, qdd at times t in [0, duration] (q None when not ``positions``)."""
        tau = np.clip(np.asarray(t, float) / self.stretch, 0.0, self.s_of_t.end_time)
        u, ud, udd = self.s_of_t(tau)
        u = np.clip(u, 0.0, 1.0)
        ud, udd = ud / self.stretch, udd / self.stretch**2
        d1, d2 = self.curve.spline(1)(u), self.curve.spline(2)(u)
        q = self.curve.spline()(u) if positions else None
        return q, d1 * ud[:, None], d2 * (ud**2)[:, None] + d1 * udd[:, None]


# TOPP-RA's grid: ``TimingSettings.grid_per_span`` points in every straight knot span of the B-spline,
# ``corner_grid`` in every span that bends (the uniform slow-down below absorbs the overshoot between grid
# points). Its solve costs ~0.15 ms per grid point. A grid that leaves TOPP-RA no finite solution (a
# single straight span with 2 points does) is refined.
MIN_GRID = 9
# At most this many grid points per curve: a car's curve through its dense samples has thousands of
# spans, and TOPP-RA on 5-11k grid points took seconds and failed numerically ("failed to find the
# maximum path acceleration"); the slow-down below covers what happens between the points.
MAX_GRID = 400
SANE = 4.0


def _toppra_grid(curve: Curve, per_span: tuple[int, int]) -> np.ndarray:
    """(straight, bending) points per span (at least MIN_GRID in all), thinned evenly to MAX_GRID."""
    counts = np.where(curve.straight_spans, *per_span)
    spans = len(counts)
    if counts.sum() - spans + 1 < MIN_GRID:
        counts = np.maximum(counts, -(-MIN_GRID // spans) + 1)
    grid = curve.grid(counts)
    if len(grid) <= MAX_GRID:
        return grid
    return grid[np.unique(np.linspace(0, len(grid) - 1, MAX_GRID).round().astype(int))]


def _resting_time(points: np.ndarray, limits: Limits) -> float:
    """The duration of the straight lines through ``points``, resting at each: per line, the slowest
    coordinate's fastest rest-to-rest motion (a triangle or trapezoid velocity profile)."""
    d = np.abs(np.diff(points, axis=0))
    v, a = limits.velocity, limits.acceleration
    per = np.where(d > v**2 / a, d / v + v / a, 2.0 * np.sqrt(d / a))
    return float(per.max(axis=1).sum()) if len(per) else 0.0


def _time_curve(curve: Curve, limits: Limits, dt: float, grid: tuple[int, int]) -> _Timed:
    """TOPP-RA on the curve, then the uniform slow-down that makes dense samples respect the limits."""
    from pydrake.multibody.optimization import Toppra

    path = _drake_bspline(curve)
    resting = None
    for per_span in (grid, (2 * grid[0], 2 * grid[1])):
        toppra = Toppra(path, _point_plant(len(limits.velocity)), _toppra_grid(curve, per_span))
        toppra.AddJointVelocityLimit(-limits.velocity, limits.velocity)
        toppra.AddJointAccelerationLimit(-limits.acceleration, limits.acceleration)
        with _drake_log_muted():  # a failure is retried on a finer grid, then timed by stops: no error to print
            s_of_t = toppra.SolvePathParameterization()
        # a grid too coarse for the curve can leave TOPP-RA a near-zero speed somewhere (durations of
        # 1e8 s): more than SANE x resting at every control point is no solution
        if s_of_t is not None:
            resting = _resting_time(curve.control, limits) if resting is None else resting
            if s_of_t.end_time() <= SANE * resting:
                break
    else:
        raise RuntimeError("TOPP-RA found no time parameterisation")
    timed = _Timed(curve, _Quadratics.of(s_of_t), 1.0)
    # probed twice as finely as the output samples, so that those mostly respect the limits too (assemble slows
    # down what still exceeds them). Against four times, seeds 0-19 on the three Fetch scenes: 3 more slow-downs
    # in 60 trajectories (74 samplings against 71), durations within 4e-5, peaks within the limits, half the probing CPU.
    probe = np.linspace(0.0, timed.duration, max(400, int(2 * timed.duration / dt)))
    _, qd, qdd = timed.evaluate(probe, positions=False)
    over_v = np.max(np.abs(qd) / limits.velocity)
    over_a = np.max(np.abs(qdd) / limits.acceleration)
    stretch = max(1.0, over_v, np.sqrt(over_a)) * (1.0 + 1e-6)
    return replace(timed, stretch=stretch)


@contextlib.contextmanager
def _drake_log_muted():
    """Drake's log records (pydrake sends them to the ``drake`` Python logger) dropped inside."""
    logger = logging.getLogger("drake")
    drop = logging.Filter("no record passes a filter named so")  # a Filter passes only records of its name
    logger.addFilter(drop)
    try:
        yield
    finally:
        logger.removeFilter(drop)


def _drake_bspline(curve: Curve):
    from pydrake.math import BsplineBasis
    from pydrake.trajectories import BsplineTrajectory

    from lazyground.motion.curve import DEGREE

    basis = BsplineBasis(DEGREE + 1, list(curve.knots))
    return BsplineTrajectory(basis, [c.reshape(-1, 1) for c in curve.control])


@functools.lru_cache(maxsize=8)
def _point_plant(dim: int):
    """A plant whose positions are the planned coordinates (a chain of prismatic joints).

    Joint velocity and acceleration limits involve no dynamics, so TOPP-RA needs only a plant
    with ``dim`` positions and q̇ = v; this keeps timing independent of the robot's plant
    (fixed joints, a planar car's joint) and of which coordinates are planned.
    """
    from pydrake.multibody.plant import MultibodyPlant
    from pydrake.multibody.tree import PrismaticJoint, SpatialInertia, UnitInertia

    plant = MultibodyPlant(0.0)
    parent = plant.world_body()
    for k in range(dim):
        body = plant.AddRigidBody(f"coordinate_{k}", SpatialInertia(1.0, np.zeros(3), UnitInertia(1.0, 1.0, 1.0)))
        plant.AddJoint(PrismaticJoint(f"coordinate_{k}", parent.body_frame(), body.body_frame(), [1.0, 0.0, 0.0]))
        parent = body
    plant.Finalize()
    return plant


@dataclass(frozen=True)
class _Rest:
    """Standing still at q (a path whose start is its goal)."""

    q: np.ndarray
    duration: float = 0.0

    def evaluate(self, t: np.ndarray):
        zero = np.zeros((len(t), len(self.q)))
        return self.q + zero, zero, zero.copy()


def _sample(parts: list, dt: float):
    """The pieces played one after another, sampled every dt and at the end: t, q, qd, qdd."""
    durations = [p.duration for p in parts]  # (read once: a line's is computed on every read)
    total = sum(durations)
    t = np.arange(0.0, total, dt)
    if not len(t) or total - t[-1] > 1e-9:
        t = np.append(t, total)
    ends = np.cumsum(durations)
    which = np.minimum(np.searchsorted(ends, t, side="left"), len(parts) - 1)
    starts = ends - durations
    # the parts play in order: each one's samples are one slice of t
    cuts = np.searchsorted(which, np.arange(len(parts) + 1), side="left")
    out = [part.evaluate(t[a:b] - start) for part, start, a, b in zip(parts, starts, cuts[:-1], cuts[1:]) if b > a]
    return (t, *(np.concatenate([o[i] for o in out]) for i in range(3)))
