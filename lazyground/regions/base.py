"""The goal-region base class, its drawing description and the registry of kinds.

A goal region GR_j of an interpretation I_i (paper Definition 2) is a box of
bounds over some coordinates; each kind says which coordinates (planned joint
values, or a pose in a reference frame), how it is drawn and serialised.
Goal sources are looked up by kind in :mod:`lazyground.goals`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from lazyground.geometry import Pose, wrap_angle

REGION_KINDS: dict[str, type["GoalRegion"]] = {}  # kind -> class, filled by @register_region


def register_region(cls: type["GoalRegion"]) -> type["GoalRegion"]:
    """Class decorator: make ``cls`` the region class of its ``kind``.

    Raises:
        ValueError: another class already has that kind.
    """
    other = REGION_KINDS.get(cls.kind)
    if other is not None and other is not cls:
        raise ValueError(f"goal region kind {cls.kind!r} is already {other.__name__}")
    REGION_KINDS[cls.kind] = cls
    return cls


@dataclass(frozen=True)
class RegionDrawing:
    """How a viewer draws a region: a translucent box, in the viewer's region colour.

    Regions whose drawings share a ``name`` are drawn once (a spot's forwards and
    reversing regions are one box).
    """

    name: str
    size: tuple[float, float, float]
    X_WB: Pose  # the box centre in world


def from_unit(lower: np.ndarray, span: np.ndarray, wrapped: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Points of bounds (:meth:`GoalRegion.unit_map`, one per row or one for all) for uniform draws ``u`` in
    [0, 1): ``lower + u * span``, wrapped to [-pi, pi) where ``wrapped``. :meth:`GoalRegion.sample` is this of
    ``rng.random(dim)``, so rows of one ``rng.random((n, dim))`` are n samples."""
    v = lower + np.asarray(u, float) * span
    return np.where(wrapped, wrap_angle(v), v)


def unit_maps(regions) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:meth:`GoalRegion.unit_map` of each of ``regions`` (of one dimension), stacked (N, dim) each, in one pass
    (512 car regions: ~0.9 ms; one numpy call per region took ~3 ms)."""
    if not len(regions):
        return np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0), bool)
    dim = len(regions[0].lower)
    if any(len(r.lower) != dim or len(r.upper) != dim for r in regions):
        raise ValueError("unit_maps: regions of different dimensions")
    lo = np.array([r.lower for r in regions], float).reshape(len(regions), dim)
    span = np.array([r.upper for r in regions], float).reshape(len(regions), dim) - lo
    wrapped = np.zeros(lo.shape, bool)
    wrapped[[j for j, r in enumerate(regions) for _ in r.wrap], [i for r in regions for i in r.wrap]] = True
    span[wrapped & (span < 0)] += 2 * np.pi  # a wrapped interval such as [3.0, -3.0]
    return lo, span, wrapped


@dataclass(frozen=True)
class GoalRegion:
    """One goal region: bounds ``lower``/``upper`` over the kind's coordinates.

    Coordinates listed in ``wrap`` are angles; their bounds may cross pi.
    Subclasses set ``kind``, are registered with :func:`register_region`, and
    implement :meth:`drawing`.
    """

    kind: ClassVar[str] = ""

    id: str
    interpretation: str
    object: str
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    label: str = ""  # e.g. "top grasp", "face +x", "forwards"
    wrap: tuple[int, ...] = ()
    attributes: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        if len(self.lower) != len(self.upper):
            raise ValueError("lower and upper bounds differ in length")
        for i, (lo, hi) in enumerate(zip(self.lower, self.upper)):
            if lo > hi and i not in self.wrap:
                raise ValueError(f"region {self.id}: lower > upper on axis {i}")

    @staticmethod
    def make(kind: str, **fields) -> "GoalRegion":
        """A region of the registered class for ``kind``.

        Raises:
            ValueError: no class is registered for ``kind``.
        """
        cls = REGION_KINDS.get(kind)
        if cls is None:
            raise ValueError(f"unknown goal region kind {kind!r} (known: {', '.join(REGION_KINDS)})")
        return cls(**fields)

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """A uniform draw in the bounds (angles wrap where listed)."""
        return from_unit(*self.unit_map(), rng.random(len(self.lower)))

    def unit_map(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(lower, span, wrapped): the bounds as :func:`from_unit` takes them (read-only arrays)."""
        cached = self.__dict__.get("_unit_map")  # (a frozen region's bounds: made once, read-only; not a field)
        if cached is None:
            cached = tuple(a[0] for a in unit_maps((self,)))
            for a in cached:
                a.setflags(write=False)
            self.__dict__["_unit_map"] = cached
        return cached

    def contains(self, v: np.ndarray, tol: float = 1e-6) -> bool:
        """Whether a vector of the kind's coordinates lies in the bounds (within ``tol``; on wrapped axes, on the
        arc from ``lower`` anticlockwise to ``upper``)."""
        v = np.asarray(v, float)
        lo, span, wrapped = self.unit_map()
        for x, a, b, s, w in zip(v, lo, self.upper, span, wrapped):
            if w:  # the angular distance from the arc's middle is at most half the arc
                if s / 2 < np.pi and abs(wrap_angle(x - (a + s / 2))) > s / 2 + tol:
                    return False
            elif not a - tol <= x <= b + tol:
                return False
        return True

    def to_json(self) -> dict:
        """The region as JSON-ready data (bounds rounded to 1e-6)."""
        return {
            "id": self.id,
            "kind": self.kind,
            "label": self.label,
            "object": self.object,
            "lower": [round(x, 6) for x in self.lower],
            "upper": [round(x, 6) for x in self.upper],
            **self._json_fields(),
        }

    def _json_fields(self) -> dict:
        """The kind's own fields for :meth:`to_json`."""
        return {}

    def drawing(self, scene) -> RegionDrawing:
        """What a viewer draws for this region in ``scene`` (a :class:`lazyground.scene.Scene`)."""
        raise NotImplementedError

    def reached(self, q: np.ndarray, world, tol: float = 1e-6) -> bool:
        """Whether planned configuration ``q`` of ``world`` (a DrakeWorld or any world the kind needs) is in the region."""
        raise NotImplementedError
