"""A smooth curve through a path, collision-checked densely (the curve, not its waypoints).

A clamped cubic B-spline whose control polygon is the path itself with two extra points
on every segment, a fraction ``blend`` of the segment in from its ends: the curve starts
and ends at the path's ends, runs on the path's segments away from the corners and rounds
each corner inside the triangle the corner spans (a B-spline lies in the convex hull of
each four consecutive control points). Less blending hugs the corners closer; the caller
tries decreasing blends until one curve is free. Wrapping coordinates are unwrapped first
so the curve turns the short way.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace

DEGREE = 3


def segment_lengths(space: ConfigSpace, q: np.ndarray) -> np.ndarray:
    """The metric distance between consecutive rows of q (vectorised ``space.distance``)."""
    e = space.embed(np.asarray(q, float))
    return np.linalg.norm(np.diff(e, axis=0), axis=1)


def unwrap_path(space: ConfigSpace, path: np.ndarray) -> np.ndarray:
    """The path with wrapping coordinates made continuous (each step the shorter arc)."""
    path = np.asarray(path, float)
    if not space.wrap.any() or len(path) < 2:
        return path.copy()
    steps = np.array([space.difference(a, b) for a, b in zip(path[:-1], path[1:])])
    return np.vstack([path[:1], path[0] + np.cumsum(steps, axis=0)])


@dataclass(frozen=True)
class Curve:
    """q(u) for u in [0, 1], with derivatives; ``control`` are the B-spline's control points.

    ``breaks`` are the distinct knots (the spline is clamped at 0 and 1): by default the
    control polygon's chord lengths averaged (de Boor), so u runs roughly with arc length
    and |dq/du| stays of one size (uniform knots gave short segments near-zero speeds,
    where TOPP-RA failed).
    """

    control: np.ndarray
    blend: float
    breaks: np.ndarray = None
    known_free: np.ndarray = None  # per knot span: it lies on a segment already checked (no check needed)

    def __post_init__(self):
        if self.breaks is None:
            c = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(self.control, axis=0), axis=1))])
            c = c / c[-1] if c[-1] > 0 else np.linspace(0.0, 1.0, len(c))
            n = len(self.control)
            inner = [np.mean(c[j : j + DEGREE]) for j in range(1, n - DEGREE)]
            object.__setattr__(self, "breaks", np.array([0.0, *inner, 1.0]))
        if self.known_free is None:
            object.__setattr__(self, "known_free", np.zeros(len(self.breaks) - 1, bool))

    @property
    def knots(self) -> np.ndarray:
        return np.concatenate([np.zeros(DEGREE), self.breaks, np.ones(DEGREE)])

    def grid(self, per_span: int) -> np.ndarray:
        """``per_span`` points in every knot span, both ends included, increasing."""
        b = self.breaks
        inner = (b[:-1, None] + np.diff(b)[:, None] * (np.arange(per_span - 1) / (per_span - 1))).ravel()
        return np.append(inner, 1.0)

    def spline(self, derivative: int = 0) -> BSpline:
        s = BSpline(self.knots, self.control, DEGREE)
        return s.derivative(derivative) if derivative else s

    def __call__(self, u) -> np.ndarray:
        return self.spline()(np.asarray(u, float))


def blended_curve(path: np.ndarray, blend: float, checked: np.ndarray | None = None) -> Curve:
    """The B-spline through an (unwrapped) path with corners rounded by ``blend`` in (0, 0.5].

    Args:
        path: (n, dim) waypoints.
        blend: how far along each segment (as a fraction) the rounding starts.
        checked: per segment, whether it was already checked at the resolution the curve will be
            (its straight knot span, which lies on it, then needs no check).
    """
    path = np.asarray(path, float)
    control = [path[0]]
    for a, b in zip(path[:-1], path[1:]):
        d = b - a
        control.extend([a + blend * d, b - blend * d, b])
    # knot span 3k depends on control points w_k, A_k, B_k, w_k+1 only: it lies on segment k
    known = np.zeros(3 * (len(path) - 1), bool)
    if checked is not None:
        known[0::3] = np.asarray(checked, bool)
    return Curve(np.array(control), blend, known_free=known)


def dense_samples(space: ConfigSpace, curve: Curve, resolution: float, max_rounds: int = 8) -> tuple[np.ndarray, np.ndarray]:
    """Parameters u and points q(u) along the curve, consecutive points at most ``resolution`` apart.

    Raises:
        RuntimeError: the spacing did not converge (a degenerate curve).
    """
    polygon = float(segment_lengths(space, curve.control).sum())
    u = np.linspace(0.0, 1.0, max(2, int(np.ceil(polygon / resolution)) + 1))
    f = curve.spline()
    for _ in range(max_rounds):
        q = f(u)
        gaps = segment_lengths(space, q)
        if gaps.max(initial=0.0) <= resolution:
            return u, q
        extra = np.maximum(1, np.ceil(gaps / resolution * 1.2).astype(int))
        u = np.concatenate([np.linspace(u[k], u[k + 1], m, endpoint=False) for k, m in enumerate(extra)] + [u[-1:]])
    raise RuntimeError("dense curve sampling did not converge")


def curve_is_free(space: ConfigSpace, checker: ValidityChecker, curve: Curve, resolution: float) -> bool:
    """Whether every point of the curve sampled at most ``resolution`` apart is free
    (skipping the knot spans that lie on segments checked before)."""
    u, q = dense_samples(space, curve, resolution)
    span = np.clip(np.searchsorted(curve.breaks, u, side="right") - 1, 0, len(curve.known_free) - 1)
    q = q[~curve.known_free[span]]
    if not len(q):
        return True
    wrapped = space.interpolate(q, q, 0.0) if space.wrap.any() else q  # the checker sees the planner's angles
    return bool(np.all(checker.configs_free(wrapped)))
