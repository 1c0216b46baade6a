"""Time parameterisation on Drake: TOPP-RA over a smooth curve through a path.

Each piece of the path (pieces end where the robot must stop: the start of a straight
approach) gets a blended B-spline (:mod:`lazyground.motion.curve`) that is checked densely
at the fine resolution, with decreasing blends; when no blend is free the piece falls back
to the piecewise-linear path with a stop at every waypoint, which is always as valid as
the path. Drake's ``Toppra`` (Pham and Pham, IEEE T-RO 2018) finds the fastest timing under
per-joint velocity and acceleration limits. TOPP-RA enforces its constraints at grid
points; the sampled trajectory is then slowed uniformly by the largest overshoot between
them, so every sample respects the limits. ``speed`` s scales the limits to s v_max and
s^2 a_max, i.e. the same motion played 1/s times slower.
"""

from __future__ import annotations

import functools
import time
from dataclasses import dataclass

import numpy as np

from lazyground.motion.curve import Curve, blended_curve, curve_is_free, unwrap_path
from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace


@dataclass(frozen=True)
class Limits:
    """Per-coordinate velocity and acceleration limits (positive, finite)."""

    velocity: np.ndarray
    acceleration: np.ndarray

    def __post_init__(self):
        for name in ("velocity", "acceleration"):
            v = np.asarray(getattr(self, name), float)
            if not (np.all(np.isfinite(v)) and np.all(v > 0)):
                raise ValueError(f"{name} limits must be positive and finite, got {v}")
            object.__setattr__(self, name, v)


@dataclass(frozen=True)
class TimingSettings:
    """``speed`` in (0, 1] scales the limits; samples every 1 / ``sample_rate`` s."""

    speed: float = 1.0
    sample_rate: float = 100.0  # Hz
    blends: tuple[float, ...] = (0.3, 0.1, 0.03)  # tried in order; then stops at waypoints

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

    Returns:
        The Trajectory, sampled every ``1 / settings.sample_rate`` s and at its end.
    """
    t0 = time.perf_counter()
    q = unwrap_path(space, path)
    scaled = Limits(limits.velocity * settings.speed, limits.acceleration * settings.speed**2)
    cuts = sorted({0, len(q) - 1, *(k for k in stops if 0 < k < len(q) - 1)})
    parts, labels, dt = [], [], 1.0 / settings.sample_rate
    for a, b in zip(cuts[:-1], cuts[1:]):
        curve, label = _free_curve(space, checker, q[a : b + 1], fine_resolution, settings.blends)
        labels.append(label)
        if curve is None:  # stop at every waypoint: straight segments are as valid as the path
            parts.extend(_time_curve(blended_curve(q[k : k + 2], 0.5), scaled, dt) for k in range(a, b))
        else:
            parts.append(_time_curve(curve, scaled, dt))
    t, qs, qd, qdd = _sample(parts, q[0], dt)
    return Trajectory(space.names, tuple(bool(w) for w in space.wrap), t, qs, qd, qdd, scaled, " + ".join(labels), time.perf_counter() - t0)


def _free_curve(space, checker, piece: np.ndarray, resolution: float, blends) -> tuple[Curve | None, str]:
    if len(piece) == 2:
        return blended_curve(piece, 0.5), "straight"
    for blend in blends:
        curve = blended_curve(piece, blend)
        if curve_is_free(space, checker, curve, resolution):
            return curve, f"blend {blend:g}"
    return None, "stops at waypoints"


@dataclass(frozen=True)
class _Timed:
    """One curve q(u) timed by u(t) on [0, duration]; ``stretch`` >= 1 slows u(t) uniformly."""

    curve: Curve
    s_of_t: object  # pydrake PiecewisePolynomial u(t)
    stretch: float

    @property
    def duration(self) -> float:
        return self.s_of_t.end_time() * self.stretch

    def evaluate(self, t: np.ndarray):
        """q, qd, qdd at times t in [0, duration]."""
        tau = np.clip(np.asarray(t, float) / self.stretch, 0.0, self.s_of_t.end_time())
        u = np.clip(self.s_of_t.vector_values(tau)[0], 0.0, 1.0)
        ud = self.s_of_t.derivative(1).vector_values(tau)[0] / self.stretch
        udd = self.s_of_t.derivative(2).vector_values(tau)[0] / self.stretch**2
        d1, d2 = self.curve.spline(1)(u), self.curve.spline(2)(u)
        return self.curve.spline()(u), d1 * ud[:, None], d2 * (ud**2)[:, None] + d1 * udd[:, None]


# TOPP-RA's grid: its solve costs ~1 ms per grid point; a coarser grid overshoots the
# acceleration limit more between grid points, which the uniform slow-down then removes
# (measured on a blended corner: 196 points, 6% overshoot; 57 points, 14%).
GRID_MAX_ERR = 0.02
GRID_MAX_SEGMENT = 0.05
GRID_MIN_POINTS = 40


def _time_curve(curve: Curve, limits: Limits, dt: float) -> _Timed:
    """TOPP-RA on the curve, then the uniform slow-down that makes dense samples respect the limits."""
    from pydrake.multibody.optimization import CalcGridPointsOptions, Toppra

    path = _drake_bspline(curve)
    options = CalcGridPointsOptions()
    options.max_err, options.max_seg_length, options.min_points = GRID_MAX_ERR, GRID_MAX_SEGMENT, GRID_MIN_POINTS
    grid = Toppra.CalcGridPoints(path, options)
    toppra = Toppra(path, _point_plant(len(limits.velocity)), grid)
    toppra.AddJointVelocityLimit(-limits.velocity, limits.velocity)
    toppra.AddJointAccelerationLimit(-limits.acceleration, limits.acceleration)
    s_of_t = toppra.SolvePathParameterization()
    if s_of_t is None:
        raise RuntimeError("TOPP-RA found no time parameterisation")
    timed = _Timed(curve, s_of_t, 1.0)
    # probed four times finer than the output samples, so those respect the limits too
    probe = np.linspace(0.0, timed.duration, max(400, int(4 * timed.duration / dt)))
    _, qd, qdd = timed.evaluate(probe)
    over_v = np.max(np.abs(qd) / limits.velocity)
    over_a = np.max(np.abs(qdd) / limits.acceleration)
    stretch = max(1.0, over_v, np.sqrt(over_a)) * (1.0 + 1e-6)
    return _Timed(curve, s_of_t, stretch)


def _drake_bspline(curve: Curve):
    from pydrake.math import BsplineBasis, KnotVectorType
    from pydrake.trajectories import BsplineTrajectory

    from lazyground.motion.curve import DEGREE

    n = len(curve.control)
    basis = BsplineBasis(DEGREE + 1, n, KnotVectorType.kClampedUniform, 0.0, 1.0)
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


def _sample(parts: list[_Timed], q0: np.ndarray, dt: float):
    """The pieces played one after another, sampled every dt and at the end."""
    total = sum(p.duration for p in parts)
    t = np.arange(0.0, total, dt)
    if not len(t) or total - t[-1] > 1e-9:
        t = np.append(t, total)
    q, qd, qdd = (np.empty((len(t), len(q0))) for _ in range(3))
    ends = np.cumsum([p.duration for p in parts])
    which = np.minimum(np.searchsorted(ends, t, side="left"), len(parts) - 1)
    starts = ends - [p.duration for p in parts]
    for k, part in enumerate(parts):
        idx = np.flatnonzero(which == k)
        if len(idx):
            q[idx], qd[idx], qdd[idx] = part.evaluate(t[idx] - starts[k])
    return t, q, qd, qdd
