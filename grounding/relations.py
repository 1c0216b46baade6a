"""Spatial relations between two objects ("the cup next to the bowl"), from scene geometry.

Directions are in the robot's frame (``spatial.robot_frame``: ahead, left); boxes are the objects'
world bounds (``spatial.world_box``), seen from the robot as the bounds of their corners.

* **next_to** (next to, beside, by, near): the ground-plane gap between the two boxes is at most the
  *reach*, ``NEAR_GAP`` (0.4 m) or half the larger footprint side of the two, whichever is more; boxes
  whose footprints overlap (by more than 1 cm both ways) are stacked — on, under, in — not side by
  side. When nothing is within reach, the one declared relaxation keeps the candidates nearest the
  landmark (ties within 1 cm) if they are within twice the reach, with a note (``nearest_gap``).
* **behind / front**: the object's centre is beyond the landmark's far side (behind) or before its
  near side (in front), as the robot looks, and the two boxes overlap sideways once the landmark's
  is widened by half its width.
* **left_of / right_of**: the object's centre is left (right) of the landmark's whole box.
* **above / below** (over, under, beneath): the object's bottom is at or above the landmark's top
  (its top at or below the landmark's bottom) and their footprints are at most ``STACK_GAP``
  (0.2 m) apart.
* **between X and Y**: the centre projects onto the segment from X's centre to Y's strictly inside
  it, at most half the segment's length off it.

A landmark phrase that matches several objects is satisfied by any of them.
"""

from __future__ import annotations

import math
from itertools import product

import numpy as np

from grounding import spatial
from lazyground.scene.schema import Scene, SceneObject

NEAR_GAP = 0.4
TIE = 0.01
STACK_GAP = 0.2
OVERLAP = 0.01
RELATIONS = ("next_to", "behind", "front", "left_of", "right_of", "above", "below", "between")


def _xy_gap(a: SceneObject, b: SceneObject) -> float:
    (alo, ahi), (blo, bhi) = spatial.world_box(a), spatial.world_box(b)
    d = np.maximum(0.0, np.maximum(alo[:2] - bhi[:2], blo[:2] - ahi[:2]))
    return float(np.hypot(*d))


def _stacked(a: SceneObject, b: SceneObject) -> bool:
    """Whether the two footprints overlap by more than ``OVERLAP`` both ways (one is on, under or in the other)."""
    (alo, ahi), (blo, bhi) = spatial.world_box(a), spatial.world_box(b)
    return bool(all(min(ahi[k], bhi[k]) - max(alo[k], blo[k]) > OVERLAP for k in (0, 1)))


def _reach(a: SceneObject, b: SceneObject) -> float:
    return max(NEAR_GAP, 0.5 * max(_footprint(a), _footprint(b)))


def nearest_gap(obj: SceneObject, landmarks: list[SceneObject]) -> float | None:
    """The smallest gap from ``obj`` to a landmark it is side by side with and within twice the reach of, or None."""
    gaps = [_xy_gap(obj, lm) for lm in landmarks
            if lm.id != obj.id and not _stacked(obj, lm) and _xy_gap(obj, lm) <= 2 * _reach(obj, lm)]
    return min(gaps, default=None)


def _footprint(o: SceneObject) -> float:
    lo, hi = spatial.world_box(o)
    return float(max(hi[:2] - lo[:2]))


def _robot_box(o: SceneObject, scene: Scene) -> tuple[float, float, float, float]:
    """(ahead min, ahead max, left min, left max) of the object's box corners in the robot frame."""
    lo, hi = spatial.world_box(o)
    pts = [spatial.robot_frame((x, y), scene) for x, y in product((lo[0], hi[0]), (lo[1], hi[1]))]
    return min(p[0] for p in pts), max(p[0] for p in pts), min(p[1] for p in pts), max(p[1] for p in pts)


def holds(relation: str, obj: SceneObject, landmark: SceneObject, scene: Scene) -> bool:
    """Whether ``obj`` stands in ``relation`` to ``landmark`` (not "between")."""
    if obj.id == landmark.id:
        return False
    if relation == "next_to":
        return not _stacked(obj, landmark) and _xy_gap(obj, landmark) <= _reach(obj, landmark)
    if relation in ("above", "below"):
        (olo, ohi), (llo, lhi) = spatial.world_box(obj), spatial.world_box(landmark)
        level = olo[2] >= lhi[2] - 1e-6 if relation == "above" else ohi[2] <= llo[2] + 1e-6
        return level and _xy_gap(obj, landmark) <= STACK_GAP
    u, v = spatial.robot_frame(obj.pose.xyz, scene)
    umin, umax, vmin, vmax = _robot_box(landmark, scene)
    if relation in ("behind", "front"):
        widen = 0.5 * (vmax - vmin)
        _, _, ovmin, ovmax = _robot_box(obj, scene)
        beside = ovmax >= vmin - widen and ovmin <= vmax + widen
        return beside and (u > umax if relation == "behind" else u < umin)
    if relation == "left_of":
        return v > vmax
    if relation == "right_of":
        return v < vmin
    raise ValueError(f"unknown relation {relation!r}")


def between(obj: SceneObject, a: SceneObject, b: SceneObject) -> bool:
    """Whether ``obj``'s centre lies between the centres of ``a`` and ``b`` (see the module docstring)."""
    if obj.id in (a.id, b.id) or a.id == b.id:
        return False
    p, pa, pb = (np.asarray(o.pose.xyz[:2], float) for o in (obj, a, b))
    seg = pb - pa
    length = float(np.hypot(*seg))
    t = float(np.dot(p - pa, seg)) / (length * length)
    off = abs(float(seg[0] * (p - pa)[1] - seg[1] * (p - pa)[0])) / length
    return 0.0 < t < 1.0 and off <= 0.5 * length


def gap(obj: SceneObject, landmark: SceneObject) -> float:
    """Ground-plane gap between the two boxes (for "the nearest is ... 0.42 m away")."""
    return _xy_gap(obj, landmark)
