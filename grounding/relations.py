"""Spatial relations between two objects ("the cup next to the bowl"), from scene geometry.

Directions are in the robot's frame (``spatial.robot_frame``: ahead, left); boxes are the objects'
world bounds (``spatial.world_box``), seen from the robot as the bounds of their corners.

* **next_to** (next to, beside, by, near): the ground-plane gap between the two boxes is at most
  ``NEAR_GAP`` (0.3 m) or half the larger footprint side of the two, whichever is more; an object
  resting on the other (or under it) is *on* it, not next to it.
* **behind / front**: the object's centre is beyond the landmark's far side (behind) or before its
  near side (in front), as the robot looks, and within the landmark's width widened by half of it.
* **left_of / right_of**: the object's centre is left (right) of the landmark's whole box.
* **above / below** (over, under, beneath): the centre is higher than the landmark's top (lower than
  its bottom) and over (under) its footprint.
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

NEAR_GAP = 0.3
RELATIONS = ("next_to", "behind", "front", "left_of", "right_of", "above", "below", "between")


def _xy_gap(a: SceneObject, b: SceneObject) -> float:
    (alo, ahi), (blo, bhi) = spatial.world_box(a), spatial.world_box(b)
    d = np.maximum(0.0, np.maximum(alo[:2] - bhi[:2], blo[:2] - ahi[:2]))
    return float(np.hypot(*d))


def _footprint(o: SceneObject) -> float:
    lo, hi = spatial.world_box(o)
    return float(max(hi[:2] - lo[:2]))


def _robot_box(o: SceneObject, scene: Scene) -> tuple[float, float, float, float]:
    """(ahead min, ahead max, left min, left max) of the object's box corners in the robot frame."""
    lo, hi = spatial.world_box(o)
    pts = [spatial.robot_frame((x, y), scene) for x, y in product((lo[0], hi[0]), (lo[1], hi[1]))]
    return min(p[0] for p in pts), max(p[0] for p in pts), min(p[1] for p in pts), max(p[1] for p in pts)


def holds(relation: str, obj: SceneObject, landmark: SceneObject, scene: Scene, support=None) -> bool:
    """Whether ``obj`` stands in ``relation`` to ``landmark`` (not "between").

    Args:
        support: a callable id -> id of the support (``Resolver.support``), to tell "on" from "next to".
    """
    if obj.id == landmark.id:
        return False
    if relation == "next_to":
        if support is not None and (support(obj) == landmark.id or support(landmark) == obj.id):
            return False
        return _xy_gap(obj, landmark) <= max(NEAR_GAP, 0.5 * max(_footprint(obj), _footprint(landmark)))
    if relation in ("above", "below"):
        lo, hi = spatial.world_box(landmark)
        c = obj.pose.xyz
        over = lo[0] <= c[0] <= hi[0] and lo[1] <= c[1] <= hi[1]
        return over and (c[2] > hi[2] if relation == "above" else c[2] < lo[2])
    u, v = spatial.robot_frame(obj.pose.xyz, scene)
    umin, umax, vmin, vmax = _robot_box(landmark, scene)
    if relation in ("behind", "front"):
        widen = 0.5 * (vmax - vmin)
        beside = vmin - widen <= v <= vmax + widen
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
