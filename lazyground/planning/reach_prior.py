"""A sound reach prior: goal positions a ball the robot carries provably cannot reach (issue #33).

If the robot's collision body contains a ball (in the plane: a disc; a car holds a vertical
cylinder as tall as its body) of radius ``r``, the robot can only reach a goal whose ball
centre that ball could reach from the start's ball centre while moving among the obstacles.
The prior answers this on a grid of cells of side ``h``, in any number of dimensions:

* a cell is *blocked* only if the ball of radius ``r - h sqrt(n) / 2`` about its centre reaches
  into an obstacle, so that the ball of radius ``r`` about every point of the cell does: a blocked
  cell holds no ball centre of a valid configuration (obstacles are under-approximated: a shape
  the caller cannot represent soundly is left out, which only frees cells);
* the grid has a ring of cells around the bounds: free, so that whatever leaves the bounds is one
  component; or blocked, for a robot whose planner holds every configuration it checks to its
  limits (``bounded``; :func:`lazyground.planning.motion_validator.samples_free` does for a car's
  curves);
* free cells are labelled in components, each cell joined to every neighbour it touches, corners
  included (``scipy.ndimage.label``): any continuous motion of a ball centre passes through
  cells that touch one after another, so a goal box none of whose cells shares a component with
  the start is unreachable.

Sound, not complete: a goal the prior keeps may still be unreachable. A planner's path is a sequence of
checked configurations; when they lie closer than a cell apart (a car's: 0.1 m, the cells 0.11 m), the
cells of consecutive ones touch, so the argument holds for the path as checked, not only for continuous motion. :class:`PlanarReach` maps
a planar robot's (x, y, heading) configuration boxes onto the grid of its disc centre.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np
from scipy import ndimage

from lazyground.regions.base import unit_maps

EPS = 1e-6  # metres: a cell is blocked only if its ball reaches this far into an obstacle (float slack)
TOLERANCE = 1e-6  # goal boxes and bounds are widened by this (ConfigRegion.contains' tolerance, limits held to 1e-9)


@dataclass(frozen=True)
class Solid:
    """A box about ``centre`` with half extents ``half`` along the columns of ``axes`` (world
    directions; identity by default), rounded by ``rounding`` (every point within it of the box):
    a ball is a point box, rounded."""

    centre: tuple[float, ...]
    half: tuple[float, ...]
    rounding: float = 0.0
    axes: tuple[tuple[float, ...], ...] | None = None
    name: str = ""

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Signed distance from ``points`` (m, n) to the solid."""
        local = np.asarray(points, float) - np.asarray(self.centre, float)
        if self.axes is not None:
            local = local @ np.asarray(self.axes, float)
        d = np.abs(local) - np.asarray(self.half, float)
        outside = np.sqrt(np.sum(np.maximum(d, 0.0) ** 2, axis=1))
        return outside + np.minimum(d.max(axis=1), 0.0) - self.rounding

    def reach(self) -> np.ndarray:
        """Half extents of the solid's axis-aligned bounding box."""
        half = np.asarray(self.half, float)
        extent = half if self.axes is None else np.abs(np.asarray(self.axes, float)) @ half
        return extent + self.rounding


@dataclass(frozen=True)
class ReachGrid:
    """Components of the cells a ball of ``radius`` may have its centre in (0: blocked)."""

    origin: np.ndarray  # the lower corner of cell (0, ..., 0)
    cell: float
    radius: float
    labels: np.ndarray = field(repr=False)
    _sums: dict = field(default_factory=dict, repr=False, compare=False)  # components -> summed-area table (meets)

    def cells(self, lower, upper) -> tuple[slice, ...]:
        """The index ranges of the cells meeting the closed box [lower, upper] (clipped to the grid:
        a box beyond it meets the free ring)."""
        lo, hi = self.index(lower), self.index(upper)
        return tuple(slice(a, b + 1) for a, b in zip(lo, hi))

    def index(self, points) -> np.ndarray:
        """The indices of the cells holding ``points`` (n values, or m rows of them), clipped to the grid."""
        top = np.array(self.labels.shape) - 1
        return np.clip(np.floor((np.asarray(points, float) - self.origin) / self.cell).astype(int), 0, top)

    def meets(self, lower, upper, components) -> np.ndarray:
        """Whether some cell meeting each box [lower[i], upper[i]] (m, n) lies in one of ``components`` (the cells
        as :meth:`cells` finds them, for m boxes at once): the count of such cells by the summed-area table of the
        components' cells (integers: exact), 2^n lookups a box."""
        lo, hi = self.index(np.atleast_2d(lower)), self.index(np.atleast_2d(upper)) + 1
        table, count = self.count_table(components), 0
        for corner in itertools.product((0, 1), repeat=lo.shape[1]):  # inclusion-exclusion over the box's corners
            at = tuple(np.where(c, hi[:, d], lo[:, d]) for d, c in enumerate(corner))
            count = count + (-1) ** (lo.shape[1] - sum(corner)) * table[at]
        return count > 0

    def count_table(self, components) -> np.ndarray:
        """The summed-area table of the cells in ``components`` (:meth:`meets`; built once per set of components,
        e.g. at set-up with the start's: a 1,044 x 1,123 lot grid takes ~20 ms)."""
        key = frozenset(int(k) for k in components if k)
        if key not in self._sums:
            table = np.zeros(tuple(d + 1 for d in self.labels.shape), np.int64)
            table[tuple(slice(1, None) for _ in self.labels.shape)] = np.isin(self.labels, list(key))
            for axis in range(table.ndim):
                np.cumsum(table, axis=axis, out=table)
            self._sums[key] = table
        return self._sums[key]

    def components(self, lower, upper) -> set[int]:
        """The components of the free cells meeting the box [lower, upper]."""
        found = np.unique(self.labels[self.cells(lower, upper)])
        return {int(k) for k in found if k}

    def blocked(self, points) -> np.ndarray:
        """Whether each point (m, n) lies in a blocked cell (its ball provably hits an obstacle)."""
        return self.labels[tuple(self.index(np.atleast_2d(np.asarray(points, float))).T)] == 0


def reach_grid(lower, upper, radius: float, solids: list[Solid], cell: float, bounded: bool = False,
               reach: tuple | None = None) -> ReachGrid:
    """The grid of cells of side ``cell`` over [lower, upper] and a ring of cells around it.

    Args:
        lower, upper: the bounds of the ball centres (n values each).
        radius: the ball's radius (a cell is blocked for ``radius - cell sqrt(n) / 2``).
        solids: the obstacles (under-approximations of them).
        cell: the cells' side.
        bounded: the ball centre never leaves [lower, upper] (a planner that holds every configuration
            to its limits): the ring is blocked. Otherwise it is free, one component with everything
            beyond the bounds (the obstacles there are not on the grid).
        reach: (a, b, radius): the ball centre stays within ``radius`` of the segment a-b (an arm's reach; a = b:
            a sphere): the cells wholly beyond are blocked (with ``bounded``, [lower, upper] around it).
    """
    # the bounds widened by TOLERANCE (a planner holds configurations to its limits within a float margin), each
    # point of them in an inner cell (floor + 1 cells: the upper bound too), one ring of cells outside
    lower, upper = np.asarray(lower, float) - TOLERANCE, np.asarray(upper, float) + TOLERANCE
    n = len(lower)
    origin = lower - cell
    shape = tuple(int(k) for k in np.floor((upper - lower) / cell).astype(int) + 3)
    free = np.ones(shape, bool)
    rho = radius - cell * math.sqrt(n) / 2 - EPS
    if rho > 0:
        for s in solids:
            _block(free, origin, cell, rho, s)
    ring = np.zeros(shape, bool)
    for axis in range(n):
        ring[(slice(None),) * axis + (0,)] = ring[(slice(None),) * axis + (-1,)] = True
    free = free & ~ring if bounded else free | ring
    if reach is not None:
        _outside_reach(free, origin, cell, *reach)
    labels, _ = ndimage.label(free, structure=np.ones((3,) * n, bool))
    return ReachGrid(origin, cell, radius, labels)


def _outside_reach(free: np.ndarray, origin: np.ndarray, cell: float, a, b, radius: float) -> None:
    """Mark the cells every point of which lies farther than ``radius`` from the segment a-b blocked (slab by slab
    along the first axis: a few full-size arrays of a 10-million-cell grid would take hundreds of MB)."""
    n = free.ndim
    a, d = np.asarray(a, float), np.asarray(b, float) - np.asarray(a, float)
    far = (radius + cell * math.sqrt(n) / 2 + EPS) ** 2
    dd = float(d @ d)
    x = [origin[k] + (np.arange(free.shape[k]) + 0.5) * cell - a[k] for k in range(n)]
    rest = [x[k].reshape([-1 if i == k else 1 for i in range(1, n)]) for k in range(1, n)]
    for i, x0 in enumerate(x[0]):
        rel = [x0] + rest
        t = 0.0 if dd == 0.0 else np.clip(sum(r * d[k] for k, r in enumerate(rel)) / dd, 0.0, 1.0)
        d2 = sum((r - t * d[k]) ** 2 for k, r in enumerate(rel))
        free[i] &= ~np.broadcast_to(d2 > far, free.shape[1:])


def _block(free: np.ndarray, origin: np.ndarray, cell: float, rho: float, solid: Solid) -> None:
    """Mark the cells whose centres lie within ``rho`` of ``solid`` blocked (:meth:`Solid.distance` below
    ``rho``, in squares and along broadcast axes: a window of cells costs a few operations per cell)."""
    c, n = np.asarray(solid.centre, float), free.ndim
    reach = solid.reach() + rho
    lo = np.maximum(np.floor((c - reach - origin) / cell - 0.5).astype(int), 0)
    hi = np.minimum(np.ceil((c + reach - origin) / cell - 0.5).astype(int), np.array(free.shape) - 1)
    if np.any(hi < lo):
        return
    rel = [(origin[k] + (np.arange(lo[k], hi[k] + 1) + 0.5) * cell - c[k]).reshape([-1 if i == k else 1 for i in range(n)])
           for k in range(n)]
    axes = None if solid.axes is None else np.asarray(solid.axes, float)
    outside = 0.0
    for k, h in enumerate(solid.half):
        local = rel[k] if axes is None else sum(rel[j] * axes[j, k] for j in range(n))
        outside = outside + np.maximum(np.abs(local) - h, 0.0) ** 2
    # inside the box every cell is hit (rho > 0); outside, the distance is sqrt(outside) - rounding
    hit = np.broadcast_to(outside < (rho + solid.rounding) ** 2, tuple(hi - lo + 1))
    free[tuple(slice(a, b + 1) for a, b in zip(lo, hi))] &= ~hit


def _arc_box(offset: np.ndarray, lo: float, span: float) -> tuple[np.ndarray, np.ndarray]:
    """The bounding box of ``offset`` turned by every angle in [lo, lo + span]."""
    rho = float(np.hypot(*offset))
    if rho == 0.0:
        return np.zeros(2), np.zeros(2)
    if span >= 2 * math.pi:
        return np.full(2, -rho), np.full(2, rho)
    a0 = math.atan2(offset[1], offset[0]) + lo
    angles = [a0, a0 + span] + [k * math.pi / 2 for k in range(math.ceil(a0 / (math.pi / 2)), math.floor((a0 + span) / (math.pi / 2)) + 1)]
    pts = rho * np.array([[math.cos(a), math.sin(a)] for a in angles])
    return pts.min(axis=0), pts.max(axis=0)


_PLANE = ((1, 2), (2, 0), (0, 1))  # per axis of a turn (x, y, z): the coordinates it turns, counterclockwise


def turned_box(lower, upper, axis: int, lo: float, span: float) -> tuple[np.ndarray, np.ndarray]:
    """The bounding box of the 3-D box [lower, upper] turned about coordinate ``axis`` by every angle in
    [lo, lo + span]: each turned box lies in the bounding box of its corners, each corner on an arc."""
    i, j = _PLANE[axis]
    out_lo, out_hi = np.array(lower, float), np.array(upper, float)
    if span == 0.0 and lo == 0.0:
        return out_lo, out_hi
    bounds = [(x, y) for x in (lower[i], upper[i]) for y in (lower[j], upper[j])]
    arcs = [_arc_box(np.array(c, float), lo, span) for c in bounds]
    out_lo[[i, j]] = np.min([a for a, _ in arcs], axis=0)
    out_hi[[i, j]] = np.max([b for _, b in arcs], axis=0)
    return out_lo, out_hi


def pose_centre_box(X_WR: np.ndarray, X_ST: np.ndarray, p_T, lower, span) -> tuple[np.ndarray, np.ndarray]:
    """The bounding box of the points X_WR · X_RS(v) · X_ST · p_T over every v = (x, y, z, roll, pitch, yaw) of the
    box from ``lower`` spanning ``span`` (a pose region's :meth:`unit_map`; X_RS(v) turns by extrinsic roll, pitch,
    yaw): the point turned about x, y, then z over each angle's range, plus the box of positions, mapped by X_WR."""
    lo, hi = turned_point_box(X_ST, p_T, lower, span)
    lower, span, X_WR = (np.asarray(a, float)[None] for a in (lower, span, X_WR))
    lo, hi = placed_boxes(lo[None], hi[None], lower, span, X_WR)
    return lo[0], hi[0]


def turned_point_box(X_ST: np.ndarray, p_T, lower, span) -> tuple[np.ndarray, np.ndarray]:
    """The bounding box of X_ST · p_T turned about x, y, then z over each angle's range of ``lower``, ``span`` (the
    first step of :func:`pose_centre_box`: it does not depend on the region's frame or positions)."""
    q = (np.asarray(X_ST, float) @ np.append(np.asarray(p_T, float), 1.0))[:3]
    lo, hi = q.copy(), q.copy()
    for axis in range(3):
        lo, hi = turned_box(lo, hi, axis, float(lower[3 + axis]), min(float(span[3 + axis]), 2 * math.pi))
    return lo, hi


_CORNER = np.array([[b >> k & 1 for k in range(3)] for b in range(8)], bool)  # the 8 corners' upper-bound choices


def placed_boxes(lo, hi, lower, span, X_WR) -> tuple[np.ndarray, np.ndarray]:
    """The rest of :func:`pose_centre_box` for m boxes at once: turned boxes ``lo``, ``hi`` (m, 3) plus the boxes of
    positions of ``lower``, ``span`` (m, 6), their corners mapped by ``X_WR`` (m, 4, 4); (lower, upper) (m, 3) each
    (the same arithmetic per box as one at a time)."""
    lo, hi = lo + lower[:, :3], hi + lower[:, :3] + span[:, :3]
    corners = np.where(_CORNER, hi[:, None, :], lo[:, None, :])  # (m, 8, 3)
    world = corners @ X_WR[:, :3, :3].transpose(0, 2, 1) + X_WR[:, None, :3, 3]
    return world.min(axis=1) - TOLERANCE, world.max(axis=1) + TOLERANCE


@dataclass(frozen=True)
class PlanarReach:
    """The reach prior of a planar robot: its disc (``offset`` from the body frame, in it) on ``grid``.

    Configurations are vectors with x, y and heading at ``index`` (the planned coordinates).
    """

    grid: ReachGrid
    start: frozenset[int]  # the start's components (empty: the start's disc is in no free cell)
    index: tuple[int, int, int]
    offset: tuple[float, float] = (0.0, 0.0)
    left_out: tuple[str, ...] = ()  # obstacles not represented (only frees cells)
    build_s: float = 0.0

    def keeps(self, region) -> bool:
        """Whether the prior lets ``region`` (a box of configurations, e.g. a ConfigRegion) be reached: False only
        when no cell of its disc centres lies in the start's component (:meth:`keeps_all` of it alone)."""
        return self.keeps_all((region,))[0]

    def keeps_all(self, regions) -> list[bool]:
        """:meth:`keeps` of each of ``regions``, all at once (#33: a 256-spot lot's 512 regions one by one took ~25 ms
        a request): the same boxes, each arc's box once per heading range, the grid looked up by :meth:`ReachGrid.meets`."""
        out = [True] * len(regions)
        ix, iy, ih = self.index
        todo = [j for j, r in enumerate(regions) if self.start and r.kind == "config" and len(r.lower) > max(self.index)]
        if not todo:
            return out
        by_dim: dict[int, list[int]] = {}  # (unit_maps stacks regions of one dimension)
        for j in todo:
            by_dim.setdefault(len(regions[j].lower), []).append(j)
        arcs: dict[bytes, tuple] = {}
        offset = np.asarray(self.offset, float)
        for rows in by_dim.values():
            lows, highs = [], []
            for lower, span in zip(*unit_maps([regions[j] for j in rows])[:2]):
                key = lower[ih:ih + 1].tobytes() + span[ih:ih + 1].tobytes()  # (by their bits: -0.0 too)
                if key not in arcs:
                    arcs[key] = _arc_box(offset, float(lower[ih]), float(span[ih]))
                lo, hi = arcs[key]
                lows.append((lower[ix] + lo[0], lower[iy] + lo[1]))
                highs.append((lower[ix] + span[ix] + hi[0], lower[iy] + span[iy] + hi[1]))
            kept = self.grid.meets(np.array(lows) - TOLERANCE, np.array(highs) + TOLERANCE, self.start)
            for j, k in zip(rows, kept):
                out[j] = bool(k)
        return out

    def centres(self, qs) -> np.ndarray:
        """The disc centres (m, 2) of configurations ``qs`` (m, dim)."""
        q = np.atleast_2d(np.asarray(qs, float))
        ix, iy, ih = self.index
        c, s = np.cos(q[:, ih]), np.sin(q[:, ih])
        ox, oy = self.offset
        return np.column_stack([q[:, ix] + c * ox - s * oy, q[:, iy] + s * ox + c * oy])
