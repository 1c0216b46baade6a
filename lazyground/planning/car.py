"""A car's configuration space (x, y, heading) whose edges are Reeds-Shepp or Dubins curves.

``CarSpace`` keeps :class:`ConfigSpace`'s interface (the planners call only
that), so goal regions, strategies and both planners are unchanged:

- ``distance`` is the length of the shortest curve (metres driven);
- ``steer`` moves at most ``step`` along that curve, ``interpolate`` and
  ``discretize`` walk it, so edges are collision-checked along the curve
  (:meth:`CarSpace.motion_validator`: a sampled validator, not the checker's straight edges);
- a returned path is its curves sampled densely (:meth:`CarSpace.dense_path`), shortened along
  curves and timed as driven (``post_processing = "curves"``: lazyground.motion.post);
- nearest neighbours: the ``nn_candidates`` nearest nodes in the inherited embedding
  (x, y, r cos th, r sin th), r the turning radius, re-ranked by curve length
  (:meth:`CarSpace.closest`). The embedding alone is a poor proxy (a sideways offset
  costs a car far more than its Euclidean distance): from its nearest node a goal step
  can drive a long loop and never arrive. Re-ranked, every free goal step ends nearer
  its goal sample. Measured on parking_2 with reward-penalty (tools/car_stats.py), seeds
  0-39: the embedding alone needed a mean 5,910 iterations (3 runs unsolved at 40,000);
  re-ranking 3 / 5 / 8 / 10 / 16 candidates a mean 1,400 / 1,069 / 1,290 / 1,247 / 1,353
  (most 6,910 / 4,727 / 5,858 / 3,860 / 5,892); seeds 40-79: 5 / 8 / 10 candidates 1,084 /
  1,102 / 1,133. Five it is: the best mean and the cheapest of the good ones.

The bidirectional planner joins goal-tree edges end to start: a reversed
Reeds-Shepp curve is a Reeds-Shepp curve, but a Dubins car cannot reverse, so there
its returned path (curves between the same waypoints, forwards) may fail the fine
re-check more often; the one-tree planner is the one to use with ``dubins``.

The curves themselves are in :mod:`lazyground.planning.curves`; the queries along them (solve, rank, steer,
sample) run compiled (:mod:`lazyground.planning.car_kernels`, #33), on words as rows (turn, signed metres).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lazyground.geometry import wrap_angle
from lazyground.planning import car_kernels, curves
from lazyground.planning.motion_validator import SampledMotionValidator
from lazyground.planning.space import ConfigSpace
from lazyground.settings import Kinematics

DENSE_SPACING = 0.1  # m: the largest gap between consecutive samples of a returned car path
NN_CANDIDATES = 5  # nearest neighbours: the embedding's nearest nodes re-ranked by curve length (see above)




@dataclass(frozen=True, eq=False)
class CarSpace(ConfigSpace):
    """(x, y, heading) with curve edges (equal and hashed by identity: it caches recent curves).

    ``radius`` is the minimum turning radius (m) of the reference point, which sits
    ``offset`` metres ahead of the configuration's origin along the heading (a car's
    rear axle centre: the point whose velocity is along the heading). The curves are
    the reference point's; the configuration's origin follows rigidly.
    """

    kinematics: Kinematics = Kinematics.REEDS_SHEPP
    radius: float = 1.0
    offset: float = 0.0
    nn_candidates: int = NN_CANDIDATES
    post_processing = "curves"  # shortcut along curves, then timed as driven (class attribute, as ConfigSpace's)

    def __post_init__(self):
        super().__post_init__()
        if self.dim != 3 or list(self.wrap) != [False, False, True]:
            raise ValueError(f"a car space needs coordinates (x, y, heading); got {self.names}")
        if not self.radius > 0.0:
            raise ValueError(f"turning radius must be positive, got {self.radius}")
        object.__setattr__(self, "kinematics", Kinematics(self.kinematics))
        object.__setattr__(self, "_words", {})
        # the origin moves faster than the reference point on arcs: hypot(1, offset / radius) times
        object.__setattr__(self, "_stretch", math.hypot(1.0, self.offset / self.radius))
        # the embedding's weights (x, y, then the heading's, ConfigSpace.embed) and the bounds with
        # within_bounds' tolerance, as floats and arrays (the numbers numpy's tests compare with)
        object.__setattr__(self, "_embed_w", (*self._w_lin.tolist(), float(self._w_ang[0])))
        lo, hi = self.lower - 1e-9, self.upper + 1e-9
        object.__setattr__(self, "_bounds", (tuple(lo.tolist()), tuple(hi.tolist())))
        object.__setattr__(self, "_bounds_arrays", (lo, hi))
        if self.kinematics is Kinematics.HOLONOMIC:
            raise ValueError("a holonomic car is a plain ConfigSpace")

    def word(self, a: np.ndarray, b: np.ndarray) -> curves.Word:
        """The shortest curve a -> b as segments (kind, signed length in metres)."""
        return tuple((curves.KIND[t], s) for t, s in self._word(a, b).tolist())

    def _word(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """:meth:`word` as rows (turn, signed length in metres)."""
        key = _key(a, b)
        w = self._words.get(key)
        if w is None:
            if self.kinematics is Kinematics.REEDS_SHEPP:
                out = np.empty((curves.MAX_SEGMENTS, 2))
                w = out[: car_kernels.solve(_vec(a), _vec(b), self.radius, self.offset, out)]
            else:
                w = _rows(curves.dubins_word(*curves.relative(self._ref(a), self._ref(b), self.radius)), self.radius)
            self._remember(key, w)
        return w

    def _remember(self, key, w: np.ndarray) -> None:
        # the planner steers a -> b, then checks the edge a -> q_new: a few recent words save
        # recomputing them (a sub-path of a shortest path is a shortest path)
        if len(self._words) >= 64:
            self._words.clear()
        self._words[key] = w

    def reference(self, q: np.ndarray) -> np.ndarray:
        """The reference point's pose (rows or one vector): shifted ``offset`` along the heading."""
        q = np.array(q, float)
        if self.offset:
            q[..., :2] += self.offset * np.stack([np.cos(q[..., 2]), np.sin(q[..., 2])], axis=-1)
        return q

    def _ref(self, q) -> tuple[float, float, float]:
        """:meth:`reference` of one configuration in scalar maths (the curve solver's input)."""
        th = float(q[2])
        return float(q[0]) + self.offset * math.cos(th), float(q[1]) + self.offset * math.sin(th), th

    def distance(self, a: np.ndarray, b: np.ndarray) -> float:
        return car_kernels.length(self._word(a, b))

    def closest(self, nodes, q: np.ndarray) -> int:
        """Index of the node of ``nodes`` whose curve to ``q`` is shortest.

        Nodes are tried in order of a lower bound on their curve length (the reference points'
        distance, and the arc that turns the heading), stopping once the bound passes the best
        length found: most candidates are ruled out without solving their curve. The winner's
        curve is remembered (the planner steers along it next).
        """
        if self.kinematics is not Kinematics.REEDS_SHEPP:
            return self._closest_dubins(nodes, q)
        out = np.empty((curves.MAX_SEGMENTS, 2))
        best, n = car_kernels.closest(np.array(nodes, float).reshape(-1, 3), _vec(q), self.radius, self.offset, out)
        self._remember(_key(nodes[best], q), out[:n])
        return best

    @property
    def compiled_nearest(self) -> bool:
        """Whether a tree's nearest-node queries go through :meth:`nearest_node` (a Reeds-Shepp car)."""
        return self.kinematics is Kinematics.REEDS_SHEPP

    def nearest_node(self, points: np.ndarray, sq: np.ndarray, n: int, ids: np.ndarray | None, nodes: np.ndarray,
                     q: np.ndarray, step: float = 0.0) -> tuple[int, np.ndarray | None, bool]:
        """A tree's node nearest q (:meth:`closest` of the ``nn_candidates`` nearest in the embedding) in one compiled
        call (:func:`lazyground.planning.car_kernels.nearest`): (its index or -1, with ``step`` the pose :meth:`steer`
        gives from it towards q, whether that reached q). ``points``, ``sq``, ``n``: a scanning nearest-neighbour
        index's arrays over ``nodes[ids]`` (``ids`` None: over ``nodes``). The words are remembered as
        :meth:`closest` and :meth:`steer` remember them."""
        q = _vec(q)
        out, head, q_new = np.empty((curves.MAX_SEGMENTS, 2)), np.empty((curves.MAX_SEGMENTS, 2)), np.empty(3)
        i, nw, nh, reached = car_kernels.nearest(points, sq, n, _NO_IDS if ids is None else ids, ids is not None, nodes,
                                                 q, self.weights, self.nn_candidates, self.radius, self.offset, step,
                                                 out, head, q_new)
        if i < 0:
            return -1, None, False
        a = nodes[i]
        self._remember(_key(a, q), out[:nw])
        if step <= 0.0 or reached:
            return i, q_new if reached else None, reached
        self._remember(_key(a, q_new), head[:nh])
        return i, q_new, False

    def _closest_dubins(self, nodes, q: np.ndarray) -> int:
        """:meth:`closest` for a Dubins car, in scalar Python (its solver is not compiled)."""
        end, r = self._ref(q), self.radius
        ref = [self._ref(a) for a in nodes]
        bound = [max(math.hypot(p[0] - end[0], p[1] - end[1]), r * abs(curves.mod2pi(end[2] - p[2]))) for p in ref]
        best, best_len, best_word = 0, math.inf, None
        for i in sorted(range(len(ref)), key=bound.__getitem__):
            if bound[i] >= best_len:
                break
            word = curves.dubins_word(*curves.relative(ref[i], end, r))
            length = curves.word_length(word) * r
            if length < best_len:
                best, best_len, best_word = i, length, word
        self._remember(_key(nodes[best], q), _rows(best_word, r))
        return best

    def poses(self, a: np.ndarray, w: np.ndarray, s) -> np.ndarray:
        """Poses at arc lengths ``s`` (metres, 1-D, clipped to the word's length) along word rows ``w`` from a."""
        s = np.atleast_1d(np.asarray(s, float)).ravel()
        out = np.empty((len(s), 3))
        car_kernels.poses(_vec(a), w, s, self.radius, self.offset, out)
        return out

    def interpolate(self, a: np.ndarray, b: np.ndarray, t) -> np.ndarray:
        """Poses at fractions ``t`` (scalar or 1-D) of the curve a -> b."""
        w = self._word(a, b)
        q = self.poses(a, w, np.asarray(t, float).ravel() * car_kernels.length(w))
        return q[0] if np.ndim(t) == 0 else q

    def discretize(self, a: np.ndarray, b: np.ndarray, resolution: float, skip_first: bool = False) -> np.ndarray:
        """Poses along the curve a -> b (both ends included, or b only) at most ``resolution`` metres apart.

        Every segment is sampled on its own, so its ends (the cusps among them) are samples. Finer than
        ``DENSE_SPACING``, a segment's samples are its dense samples' (:meth:`dense_path`) each piece between
        them sampled evenly: a path checked here at ``resolution`` is checked at the very configurations a
        re-check of its dense form at ``resolution`` takes (else a sliver of obstacle between one set of
        samples could lie on the other: parking_2, seed 1033071480, a 3.7 mm graze of a wall).
        """
        return car_kernels.discretize(_vec(a), _vec(b), self._word(a, b), resolution, skip_first, self._stretch,
                                      DENSE_SPACING, self.radius, self.offset)

    def steer(self, a: np.ndarray, b: np.ndarray, step: float) -> tuple[np.ndarray, bool]:
        w = self._word(a, b)
        if car_kernels.length(w) <= step:
            return np.array(b, float), True
        q, head = np.empty(3), np.empty((curves.MAX_SEGMENTS, 2))
        n = car_kernels.steer(_vec(a), w, step, self.radius, self.offset, q, head)
        self._remember(_key(a, q), head[:n])  # (the word's first step metres: a shortest path's prefix)
        return q, False

    @property
    def drives_straight(self) -> bool:
        """Whether the bidirectional planner's goal trees take :meth:`straight_step`: a Reeds-Shepp car
        (a Dubins goal tree is driven in reverse, its edges end to start, and cannot back out)."""
        return self.kinematics is Kinematics.REEDS_SHEPP

    def straight_step(self, a: np.ndarray, towards: np.ndarray, step: float) -> np.ndarray | None:
        """The pose ``step`` metres straight along a's heading, forwards or backwards (the side ``towards``
        lies on), or None if it is out of bounds.

        How a car leaves a tight spot (a parking bay: straight out along its axis, issue #33); the
        bidirectional planner tries it when a goal tree's curve step is blocked."""
        c, s = math.cos(float(a[2])), math.sin(float(a[2]))
        d = step if (towards[0] - a[0]) * c + (towards[1] - a[1]) * s >= 0.0 else -step
        q = np.array([a[0] + d * c, a[1] + d * s, a[2]], float)
        return q if self.within_bounds(q) else None

    def embed(self, q: np.ndarray) -> np.ndarray:
        """:meth:`ConfigSpace.embed`; one pose in scalar maths (the same products: numpy's overhead would dominate)."""
        if np.ndim(q) != 1:
            return super().embed(q)
        th, w = float(q[2]), self._embed_w
        return np.array((float(q[0]) * w[0], float(q[1]) * w[1], w[2] * math.cos(th), w[2] * math.sin(th)))

    def within_bounds(self, q: np.ndarray, tol: float = 1e-9) -> bool:
        if tol != 1e-9 or np.ndim(q) != 1:
            return super().within_bounds(q, tol)
        lo, hi = self._bounds
        return lo[0] <= q[0] <= hi[0] and lo[1] <= q[1] <= hi[1] and lo[2] <= q[2] <= hi[2]

    def all_inside(self, qs: np.ndarray) -> bool:
        """Whether every row of qs is within the bounds (1e-9 of them: :func:`samples_free`'s test)."""
        return car_kernels.inside(qs, *self._bounds_arrays)

    def path_length(self, path: np.ndarray) -> float:
        return float(sum(self.distance(a, b) for a, b in zip(path[:-1], path[1:])))

    def motion_validator(self, checker) -> SampledMotionValidator:
        """Curve edges, checked at this space's samples along them (the checker interpolates straight lines)."""
        return SampledMotionValidator(self, checker)

    def dense_path(self, path: np.ndarray, spacing: float = DENSE_SPACING) -> np.ndarray:
        """The path's curves sampled at most ``spacing`` metres apart (waypoints kept): what the car drives."""
        parts = [self.discretize(a, b, spacing, skip_first=k > 0) for k, (a, b) in enumerate(zip(path[:-1], path[1:]))]
        return np.vstack(parts) if parts else np.array(path, float)

    def cusps(self, dense: np.ndarray) -> int:
        """Gear changes along a dense path of this space (see :func:`gear_changes`)."""
        return gear_changes(self.reference(dense))

    def cusp_indices(self, dense: np.ndarray) -> tuple[int, ...]:
        """The waypoints of a dense path where the direction of travel flips (where a car stops)."""
        return cusp_indices(self.reference(dense))


def _key(a, b) -> tuple[bytes, bytes]:
    """The curve cache's key of a -> b."""
    return np.asarray(a, float).tobytes(), np.asarray(b, float).tobytes()


_NO_IDS = np.zeros(0, np.int64)


def _vec(q) -> np.ndarray:
    """q as the kernels take a pose: a float vector (no copy if it is one)."""
    return np.asarray(q, float)


def _rows(word: curves.Word, radius: float) -> np.ndarray:
    """A unit-radius word as rows (turn, signed length in metres)."""
    return np.array([(curves.TURN[k], s * radius) for k, s in word]).reshape(-1, 2)


def drive_profile(path: np.ndarray) -> np.ndarray:
    """Per step of a dense path of reference-point poses: +1 forwards, -1 reverse, 0 standing."""
    d = np.diff(path[:, :2], axis=0)
    mid = path[:-1, 2] + 0.5 * wrap_angle(np.diff(path[:, 2]))
    along = d[:, 0] * np.cos(mid) + d[:, 1] * np.sin(mid)
    return np.sign(np.where(np.abs(along) < 1e-12, 0.0, along))


def gear_changes(path: np.ndarray) -> int:
    """Cusps of a dense path of reference-point poses: how often the direction of travel flips."""
    return len(cusp_indices(path))


def cusp_indices(path: np.ndarray) -> tuple[int, ...]:
    """Waypoints of a dense path of reference-point poses where the direction of travel flips."""
    g = drive_profile(path)
    moving = np.flatnonzero(g)  # steps that move (step k runs from waypoint k to k + 1)
    flips = moving[1:][g[moving[1:]] != g[moving[:-1]]]
    return tuple(int(k) for k in flips)


def car_space(base: ConfigSpace, kinematics: Kinematics, radius: float, offset: float = 0.0) -> CarSpace:
    """A CarSpace over ``base``'s bounds (registered in :data:`lazyground.planning.kinematics.SPACES`).

    Nearest neighbours weigh the heading by the turning radius (see the module docstring). A Reeds-Shepp car's
    compiled queries are loaded here, once per process, rather than in its first search (car_kernels.warm_up).
    """
    if Kinematics(kinematics) is Kinematics.REEDS_SHEPP:
        car_kernels.warm_up()
    return CarSpace(base.names, base.lower, base.upper, np.array([1.0, 1.0, radius]), base.wrap,
                    kinematics=kinematics, radius=float(radius), offset=float(offset))
