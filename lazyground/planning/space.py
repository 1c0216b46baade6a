"""Configuration spaces over numpy arrays: sampling, metric, interpolation.

One class covers the holonomic car (x, y, heading) and arms: coordinates are bounded
intervals, some of which may be wrapping angles. The metric is Euclidean in an
embedding (angles as weighted unit circles), so a k-d tree over the embedding
answers nearest-neighbour queries exactly.

A space owns its motion, as OMPL's ``StateSpace``: interpolation, the motion
validator built from a checker (:meth:`ConfigSpace.motion_validator`), the path it
returns (:meth:`ConfigSpace.dense_path`) and the post-processing its paths get
(:attr:`ConfigSpace.post_processing`, a key of ``lazyground.motion.post``). A space
with other edges (the car's curves, :mod:`lazyground.planning.car`) overrides these;
see docs/spaces.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lazyground.geometry import wrap_angle
from lazyground.planning.motion_validator import MotionValidator

FLOAT_PATH_MAX_DIM = 16  # OpenBLAS's dot sums 16 or more entries in blocks: numpy's rounding, not a loop's
_KERNELS: list = []  # lazyground.planning.linear_kernels once loaded (ConfigSpace.kernels; not on the space: it pickles)


def _load_kernels():
    from lazyground.planning import linear_kernels

    _KERNELS.append(linear_kernels)
    return linear_kernels


@dataclass(frozen=True)
class ConfigSpace:
    """Bounded coordinates with per-coordinate metric weights; ``wrap`` marks angles."""

    post_processing = "straight"  # shortcut by straight segments, then time (lazyground.motion.post)
    nn_candidates = 1  # nearest neighbours: the embedding's nearest is the nearest (see Tree.nearest)

    names: tuple[str, ...]
    lower: np.ndarray
    upper: np.ndarray
    weights: np.ndarray = None  # default: ones
    wrap: np.ndarray = None  # bool mask; default: none
    _lin: np.ndarray = field(init=False, repr=False)
    _ang: np.ndarray = field(init=False, repr=False)
    _w2: np.ndarray = field(init=False, repr=False)
    _w2_lin: np.ndarray = field(init=False, repr=False)
    _w2_ang: np.ndarray = field(init=False, repr=False)
    _w_lin: np.ndarray = field(init=False, repr=False)
    _w_ang: np.ndarray = field(init=False, repr=False)
    _span: np.ndarray = field(init=False, repr=False)
    _w2_list: tuple | None = field(init=False, repr=False)  # the squared weights as floats: the float path (below)
    embeds_as_is: bool = field(init=False, repr=False)  # the embedding is the coordinates (no angles, unit weights)
    unit_linear: bool = field(init=False, repr=False)  # embeds_as_is, < 16 coordinates: lazyground.planning.linear_kernels

    def __post_init__(self):
        n = len(self.names)
        lower, upper = np.asarray(self.lower, float), np.asarray(self.upper, float)
        weights = np.ones(n) if self.weights is None else np.asarray(self.weights, float)
        wrap = np.zeros(n, bool) if self.wrap is None else np.asarray(self.wrap, bool)
        if not (lower.shape == upper.shape == weights.shape == wrap.shape == (n,)):
            raise ValueError("space arrays must all have one entry per coordinate")
        if np.any(~np.isfinite(lower[~wrap])) or np.any(~np.isfinite(upper[~wrap])):
            raise ValueError(f"unbounded coordinate in {self.names}: give limits in the scene")
        lower = np.where(wrap, -np.pi, lower)
        upper = np.where(wrap, np.pi, upper)
        for name, value in (("lower", lower), ("upper", upper), ("weights", weights), ("wrap", wrap)):
            object.__setattr__(self, name, value)
        object.__setattr__(self, "_lin", np.flatnonzero(~wrap))
        object.__setattr__(self, "_ang", np.flatnonzero(wrap))
        object.__setattr__(self, "_w2", weights**2)
        object.__setattr__(self, "_w2_lin", weights[~wrap] ** 2)
        object.__setattr__(self, "_w2_ang", weights[wrap] ** 2)
        object.__setattr__(self, "_w_lin", weights[~wrap])
        object.__setattr__(self, "_w_ang", weights[wrap])
        object.__setattr__(self, "_span", upper - lower)
        # Every coordinate linear and fewer than 16 of them: distances and probes on Python floats, the same IEEE
        # operations in the same order as numpy's (np.dot below 16 entries sums in order; checked bit for bit,
        # tests/unit/test_space_floats.py), without numpy's call overhead on tiny arrays (#31).
        fast = not wrap.any() and n < FLOAT_PATH_MAX_DIM
        object.__setattr__(self, "_w2_list", tuple((weights**2).tolist()) if fast else None)
        object.__setattr__(self, "embeds_as_is", not wrap.any() and bool(np.all(weights == 1.0)))
        object.__setattr__(self, "unit_linear", self.embeds_as_is and fast)

    @property
    def kernels(self):
        """:mod:`lazyground.planning.linear_kernels` in a unit-weight linear space (every arm here), else None
        (numba: imported at the first ask by such a space; a car never loads it)."""
        if not self.unit_linear:
            return None
        return _KERNELS[0] if _KERNELS else _load_kernels()

    @property
    def dim(self) -> int:
        return len(self.names)

    @property
    def embed_dim(self) -> int:
        return len(self._lin) + 2 * len(self._ang)

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        q = rng.random(len(self._span))
        q *= self._span  # (in place: lower + r * span, the same numbers without two temporaries)
        q += self.lower
        return q

    def embed(self, q: np.ndarray) -> np.ndarray:
        """Points whose Euclidean distance is the space's metric (rows or one vector)."""
        q = np.asarray(q, float)
        if not len(self._ang):  # every coordinate linear: no gather needed (the same products)
            return q * self.weights
        lin = q[..., self._lin] * self._w_lin
        a, w = q[..., self._ang], self._w_ang
        return np.concatenate([lin, w * np.cos(a), w * np.sin(a)], axis=-1)

    def difference(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """b - a, with angles along the shorter arc."""
        d = np.asarray(b, float) - np.asarray(a, float)
        if len(self._ang):
            d[..., self._ang] = wrap_angle(d[..., self._ang])
        return d

    def distance(self, a: np.ndarray, b: np.ndarray) -> float:
        """The embedding's Euclidean distance, computed without embedding.

        An angle difference d weighted w contributes the chord (2 w sin(d/2))^2
        = 2 w^2 (1 - cos d), which needs no wrapping.
        """
        w2 = self._w2_list
        if w2 is not None:
            s = 0.0
            for w, x, y in zip(w2, np.asarray(a, float).tolist(), np.asarray(b, float).tolist()):
                v = y - x
                s += w * (v * v)
            return math.sqrt(s)
        return self._length(np.subtract(b, a))

    def _length(self, d: np.ndarray) -> float:
        """The metric length of a difference vector (angles wrapped or not: the chord ignores turns)."""
        if not len(self._ang):
            return math.sqrt(np.dot(self._w2, d * d))  # (the same rounding as np.sqrt)
        lin = d[self._lin]
        return float(np.sqrt(np.dot(self._w2_lin, lin * lin) + np.dot(self._w2_ang, 2.0 * (1.0 - np.cos(d[self._ang])))))

    def interpolate(self, a: np.ndarray, b: np.ndarray, t) -> np.ndarray:
        """Configurations a + t (b - a) along shortest arcs; ``t`` scalar or 1-D."""
        if self._w2_list is not None and isinstance(t, float):  # (a lazy probe: Python floats, the same numbers)
            return np.array([x + t * (y - x) for x, y in zip(np.asarray(a, float).tolist(), np.asarray(b, float).tolist())])
        t = np.asarray(t, float)
        q = np.asarray(a, float) + np.multiply.outer(t, self.difference(a, b))
        if len(self._ang):
            q[..., self._ang] = wrap_angle(q[..., self._ang])
        return q

    def discretize(self, a: np.ndarray, b: np.ndarray, resolution: float, skip_first: bool = False) -> np.ndarray:
        """Configurations from a to b (both included, or b only) no more than ``resolution`` apart."""
        n = max(1, int(np.ceil(self.distance(a, b) / resolution)))
        t = np.arange(1 if skip_first else 0, n + 1) / n
        return self.interpolate(a, b, t)

    def discretize_path(self, path: np.ndarray, segments, resolution: float) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`discretize` of the path's segments ``segments`` (ascending) stacked, a vertex shared by two of
        them once; and each row's segment index.

        Linear straight segments go in a few numpy calls over all of them: the same numbers as segment by
        segment (a + t (b - a) with t = i / n, elementwise), without a dozen numpy calls per segment (#31);
        in a unit-weight space in one compiled call (:attr:`kernels`), the same numbers again."""
        segments = list(segments)
        kernels = self.kernels if type(self).discretize is ConfigSpace.discretize else None
        if kernels is not None and segments:
            try:
                return kernels.discretize_path(path, np.array(segments, np.int64), resolution)
            except TypeError:  # (path not a contiguous float array: numpy's calls below)
                pass
        skips = [i > 0 and segments[i - 1] == k - 1 for i, k in enumerate(segments)]
        if self._w2_list is None or type(self).discretize is not ConfigSpace.discretize or not segments:
            chunks = [self.discretize(path[k], path[k + 1], resolution, skip_first=skip) for k, skip in zip(segments, skips)]
            owner = [np.full(len(qs), k) for k, qs in zip(segments, chunks)]
            return (np.vstack(chunks), np.concatenate(owner)) if chunks else (np.empty((0, self.dim)), np.empty(0, int))
        path = np.asarray(path, float)
        ks = np.array(segments)
        ns = np.array([max(1, int(np.ceil(self.distance(path[k], path[k + 1]) / resolution))) for k in segments])
        first = np.array(skips, int)
        counts = ns + 1 - first
        rows = np.repeat(np.arange(len(ks)), counts)
        i = np.arange(len(rows)) - np.repeat(np.cumsum(counts) - counts, counts) + first[rows]
        a = path[ks][rows]
        return a + (i / ns[rows])[:, None] * (path[ks + 1][rows] - a), ks[rows]

    def steer(self, a: np.ndarray, b: np.ndarray, step: float) -> tuple[np.ndarray, bool]:
        """Move from a towards b by at most ``step``; returns (q, reached_b)."""
        if not len(self._ang):  # no angles: the same numbers in fewer numpy calls
            a = np.asarray(a, float)
            diff = np.subtract(b, a)
            d = math.sqrt(np.dot(self._w2, diff * diff))
            if d <= step:
                return np.array(b, float), True
            diff *= step / d  # (in place: a + (step / d) * diff as below)
            diff += a
            return diff, False
        diff = self.difference(a, b)
        d = self._length(diff)
        if d <= step:
            return np.array(b, float), True
        q = np.asarray(a, float) + (step / d) * diff  # as interpolate(a, b, step / d), sharing the difference
        if len(self._ang):
            q[self._ang] = wrap_angle(q[self._ang])
        return q, False

    def closest(self, nodes, q: np.ndarray) -> int:
        """Index of the node of ``nodes`` (a non-empty sequence) nearest to ``q`` in this space's distance."""
        return int(np.argmin([self.distance(a, q) for a in nodes]))

    def clip(self, q: np.ndarray) -> np.ndarray:
        return np.clip(q, self.lower, self.upper)

    def within_bounds(self, q: np.ndarray, tol: float = 1e-9) -> bool:
        return bool((q >= self.lower - tol).all() and (q <= self.upper + tol).all())  # methods: np.all costs ~2x here

    def path_length(self, path: np.ndarray) -> float:
        kernels = self.kernels
        if kernels is not None and len(path) > 1:  # (the segments' distances in one compiled call, then the same sum)
            out = np.empty(len(path) - 1)
            try:
                kernels.segment_lengths(path, out)
                return float(sum(out.tolist()))
            except TypeError:  # (not a contiguous float array)
                pass
        return float(sum(self.distance(a, b) for a, b in zip(path[:-1], path[1:])))

    def motion_validator(self, checker) -> MotionValidator:
        """The validator of this space's edges over ``checker``: straight edges, the checker's own edge check."""
        return MotionValidator(self, checker)

    def dense_path(self, path: np.ndarray) -> np.ndarray:
        """The path a planner returns for these waypoints: themselves (straight edges need no samples)."""
        return path
