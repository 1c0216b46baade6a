"""A smooth curve through a path, collision-checked densely (the curve, not its waypoints).

A clamped cubic B-spline whose control polygon is the path itself with two extra points
on every segment, a fraction ``blend`` of the segment in from its ends: the curve starts
and ends at the path's ends, runs on the path's segments away from the corners and rounds
each corner inside the triangle the corner spans (a B-spline lies in the convex hull of
each four consecutive control points). Less blending hugs the corners closer; the caller
tries decreasing blends until one curve is free. Wrapping coordinates are unwrapped first
so the curve turns the short way. The curve is checked where it is timed
(:mod:`lazyground.motion.trajectory`), on the samples a controller receives.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import BSpline

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

    def __post_init__(self):
        if self.breaks is None:
            c = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(self.control, axis=0), axis=1))])
            c = c / c[-1] if c[-1] > 0 else np.linspace(0.0, 1.0, len(c))
            n = len(self.control)
            inner = [np.mean(c[j : j + DEGREE]) for j in range(1, n - DEGREE)]
            object.__setattr__(self, "breaks", np.array([0.0, *inner, 1.0]))

    @property
    def knots(self) -> np.ndarray:
        return np.concatenate([np.zeros(DEGREE), self.breaks, np.ones(DEGREE)])

    def grid(self, per_span) -> np.ndarray:
        """``per_span`` points in every knot span (an int, or one per span), both ends included, increasing."""
        b = self.breaks
        counts = np.broadcast_to(np.asarray(per_span, int), (len(b) - 1,))
        inner = [b[j] + (b[j + 1] - b[j]) * np.arange(m - 1) / (m - 1) for j, m in enumerate(counts)]
        return np.append(np.concatenate(inner), 1.0)

    @functools.cached_property
    def straight_spans(self) -> np.ndarray:
        """Per knot span, whether the curve runs straight there (its four control points on one line):
        on a blended path, the middle of every segment."""
        c = self.control
        if len(c) < DEGREE + 1:
            return np.zeros(len(self.breaks) - 1, bool)
        four = np.stack([c[k : len(c) - DEGREE + k] for k in range(DEGREE + 1)], axis=1)  # (spans, 4, dim)
        d = four[:, -1] - four[:, 0]
        length = np.linalg.norm(d, axis=1)
        unit = d / np.where(length > 0, length, 1.0)[:, None]
        off = four - four[:, :1]
        across = off - np.einsum("skd,sd->sk", off, unit)[:, :, None] * unit[:, None, :]
        return (length > 0) & (np.max(np.linalg.norm(across, axis=2), axis=1) <= 1e-9 * np.maximum(1.0, length))

    def spline(self, derivative: int = 0) -> BSpline:
        return self._splines[derivative]

    @functools.cached_property
    def _splines(self) -> tuple[BSpline, BSpline, BSpline]:
        """q(u) and its first two derivatives (built once: timing evaluates them many times).

        The derivatives' coefficients are scipy's (``BSpline.derivative``: the same formula and float
        operations, so the same numbers) without its per-call checks, which cost ~3x the arithmetic here.
        """
        t, c, k = self.knots, np.asarray(self.control, float), DEGREE
        splines = [BSpline.construct_fast(t, c, k)]
        c = np.concatenate([c, np.zeros((len(t) - len(c),) + c.shape[1:])])  # scipy pads c to len(t)
        for _ in range(2):
            c = (c[1 : -1 - k] - c[: -2 - k]) * k / (t[k + 1 : -1] - t[1 : -k - 1])[:, None]
            c = np.concatenate([c, np.zeros((k,) + c.shape[1:])])
            t, k = t[1:-1], k - 1
            splines.append(BSpline.construct_fast(t, c, k))
        return tuple(splines)

    def __call__(self, u) -> np.ndarray:
        return self.spline()(np.asarray(u, float))


def blended_curve(path: np.ndarray, blend: float) -> Curve:
    """The B-spline through an (unwrapped) path with corners rounded by ``blend`` in (0, 0.5]."""
    path = np.asarray(path, float)
    control = [path[0]]
    for a, b in zip(path[:-1], path[1:]):
        d = b - a
        control.extend([a + blend * d, b - blend * d, b])
    return Curve(np.array(control), blend)

