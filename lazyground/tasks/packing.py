"""Where a placement should go when more objects follow (issue #30): leave room, keep clear.

Two rules, both about the placement's position on the surface (the x, y of a placement
region's draw, in the region's frame: the surface's top centre):

* **pack**: when objects are still to be put down after this one, each placement attempt
  draws ``draws`` candidate positions and tries the one farthest from the centre of the
  surface's free area (the area no object already on it covers). On an empty surface the
  first object goes towards an edge or corner, the next one beside it, so one free
  stretch stays as large as it can for what follows. ``draws`` 1 is a uniform placement.
* **keep clear**: after a backtrack (:mod:`lazyground.tasks.several`), the positions where the
  re-planned step's earlier placements stood are ruled out: a candidate within the earlier
  object's footprint radius of one is not tried (the IK source's "kept clear"), so the re-planned
  step puts its object at least that far away. (Ruling out every overlapping placement, twice the
  radius, left no room at all on a narrow ledge.)

Footprints are discs: an object's half-diagonal in x, y (a box) or its radius (a cylinder).
The IK goal source applies the preference to the attempts its batch solver draws (the default
``ik_solver``); with ``snopt`` / ``ipopt`` placements are drawn uniformly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.geometry import Pose
from lazyground.scene.schema import Scene, SceneObject

GRID = 25  # cells per side of the grid the free area's centre is estimated on
ABOVE = 0.3  # m: an object whose centre is at most this far above a surface counts as on it


def footprint(obj: SceneObject) -> float:
    """Radius of the disc an object covers on a surface (its half-diagonal in x, y)."""
    hx, hy, _ = obj.geometry.half_extents()
    return float(np.hypot(hx, hy)) if obj.geometry.cylinder is None else float(obj.geometry.cylinder.radius)


@dataclass(frozen=True)
class Preference:
    """Per placement region (the IK source's index): the free area's centre and the discs to keep clear.

    Handed to the IK goal source as ``source.prefer`` (:class:`lazyground.drake.ik.source.IKGoalSource`).
    """

    draws: int  # candidates per attempt (1: no packing, uniform)
    centres: np.ndarray  # (R, 2) free-area centre per region, in its frame
    clear: tuple[np.ndarray, ...]  # per region: (K, 3) discs (x, y, radius) no candidate may overlap

    def score(self, j: np.ndarray, V: np.ndarray) -> np.ndarray:
        """Distance of draws ``V`` (..., N, 6) of regions ``j`` (N,) from their free area's centre; -inf when ruled out."""
        d = np.linalg.norm(V[..., :2] - self.centres[j], axis=-1)
        return np.where(self._blocked(j, V), -np.inf, d)

    def pick(self, j: np.ndarray, V: np.ndarray) -> np.ndarray:
        """The best of ``draws`` candidates ``V`` (draws, N, 6) per attempt, (N, 6)."""
        best = np.argmax(self.score(j, V), axis=0)
        return V[best, np.arange(V.shape[1])]

    def avoided(self, j: np.ndarray, V: np.ndarray) -> np.ndarray:
        """Which draws ``V`` (N, 6) overlap a disc to keep clear, (N,) bool."""
        return self._blocked(j, V)

    def _blocked(self, j: np.ndarray, V: np.ndarray) -> np.ndarray:
        out = np.zeros(V.shape[:-1], bool)
        for r in np.unique(j):
            discs = self.clear[r]
            if len(discs) == 0:
                continue
            mine = j == r
            p = V[..., mine, None, :2]  # (..., n, 1, 2)
            out[..., mine] = np.any(np.linalg.norm(p - discs[:, :2], axis=-1) < discs[:, 2], axis=-1)
        return out


def preference(scene: Scene, carried: str, regions, draws: int, keep_clear: tuple[tuple[float, float, float, float], ...] = ()
               ) -> Preference:
    """The placement preference for carrying ``carried`` to ``regions`` (placement regions) in ``scene``.

    Args:
        scene: the scene as the earlier steps left it (placed objects where they were put).
        carried: the carried object's id (its footprint widens every disc).
        regions: the placement regions, in the IK source's order.
        draws: candidates per attempt (``TaskSettings.placement_draws``; 1 when nothing follows).
        keep_clear: world discs (x, y, z, radius) no candidate position may lie in (earlier placements a
            backtrack undid, each with its object's footprint radius: the new placement moves at least that far).
    """
    r_carried = footprint(scene.object(carried))
    centres, clear = [], []
    for region in regions:
        X_RW = region.X_WR.inverse()
        lo, hi = np.asarray(region.lower[:2], float), np.asarray(region.upper[:2], float)
        others = [(_in(X_RW, o.pose.xyz), footprint(o)) for o in scene.objects if o.id not in (carried, region.object)]
        on = [(p[:2], r) for p, r in others if 0.0 <= p[2] <= ABOVE and np.all(p[:2] >= lo - r - r_carried)
              and np.all(p[:2] <= hi + r + r_carried)]
        centres.append(_free_centre(lo, hi, [(p, r + r_carried) for p, r in on]))
        discs = [(*_in(X_RW, (x, y, z))[:2], r) for x, y, z, r in keep_clear
                 if abs(_in(X_RW, (x, y, z))[2]) <= ABOVE]
        clear.append(np.array(discs, float).reshape(-1, 3))
    return Preference(max(1, int(draws)), np.array(centres, float).reshape(-1, 2), tuple(clear))


def _in(X_RW: Pose, p) -> np.ndarray:
    """A world point in a region's frame."""
    return np.asarray(X_RW.transform_points(np.asarray(p, float).reshape(1, 3)), float).reshape(3)


def _free_centre(lo: np.ndarray, hi: np.ndarray, discs: list) -> np.ndarray:
    """Centre of the part of the box [lo, hi] no disc (centre, radius) covers (the box's centre if all is covered)."""
    xs, ys = np.linspace(lo[0], hi[0], GRID), np.linspace(lo[1], hi[1], GRID)
    P = np.stack(np.meshgrid(xs, ys), axis=-1).reshape(-1, 2)
    free = np.ones(len(P), bool)
    for c, r in discs:
        free &= np.linalg.norm(P - c, axis=1) >= r
    return P[free].mean(axis=0) if free.any() else (lo + hi) / 2
