"""The request corpus's oracle: what a described object set IS in a scene, computed from the scene's
geometry and attributes alone (#29). It never imports ``grounding``: it re-derives each documented
meaning (docs/requests.md) from the raw scene data with its own code, so a grounder bug shows as a
disagreement instead of being copied into the expectation.

A ``Desc`` is the meaning of one noun phrase (type, colour, support, relation, id, closest, ordinal,
exclusion); ``expected(scene, desc, role)`` is the set of object ids it names.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

PICKABLE = {"can", "cup", "box", "bottle"}
SUPPORTS = {"table", "shelf", "counter", "cabinet"}
SPOT = "parking_spot"
TOUCH, NEAR, OVERLAP, TIE = 0.03, 0.4, 0.01, 0.01


@dataclass(frozen=True)
class Desc:
    """The meaning of a noun phrase; None/empty fields do not narrow."""

    type: str | None = None
    id: str | None = None
    id_num: int | None = None  # "can 3", "spot b1" -> tail "b1" in id_tail
    id_tail: str | None = None
    colour: str | None = None
    not_colour: str | None = None
    on: "Desc | None" = None
    not_on: "Desc | None" = None
    rel: tuple | None = None  # ("next_to" | "left_of" | "right_of", Desc)
    between: tuple | None = None  # (Desc, Desc)
    closest: bool = False
    ordinal: tuple | None = None  # (n, "left" | "right")
    except_colour: str | None = None


def _rot(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def _half(o):
    g = o.geometry
    if g.box is not None:
        return [v / 2 for v in g.box]
    if g.cylinder is not None:
        return [g.cylinder.radius, g.cylinder.radius, g.cylinder.length / 2]
    if g.sphere is not None:
        return [g.sphere.radius] * 3
    raise ValueError(f"{o.id}: the oracle knows boxes, cylinders and spheres")


def bounds(o):
    """World axis-aligned bounds (lo, hi) of the object's shape."""
    h, R, c = _half(o), _rot(o.pose.rpy), o.pose.xyz
    pts = []
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                v = (sx * h[0], sy * h[1], sz * h[2])
                pts.append([c[i] + sum(R[i][j] * v[j] for j in range(3)) for i in range(3)])
    return [min(p[i] for p in pts) for i in range(3)], [max(p[i] for p in pts) for i in range(3)]


def robot_pose(scene):
    """(x, y, yaw) the robot stands at: its base, else its start (x, y and a *_qz / *_yaw heading)."""
    b = scene.robot.base
    if b is not None:
        return b.xyz[0], b.xyz[1], b.rpy[2]
    s = scene.robot.start
    pick = lambda ends: next((v for k, v in s.items() if k.endswith(ends) or k in (e.strip("_") for e in ends)), 0.0)
    return pick(("_x",)), pick(("_y",)), pick(("_qz", "_theta", "_yaw"))


def lateral(scene, x, y):
    """The point's left coordinate in the robot's frame (+ is left)."""
    rx, ry, yaw = robot_pose(scene)
    return -math.sin(yaw) * (x - rx) + math.cos(yaw) * (y - ry)


def support(scene, o):
    """The id the object rests on (or "floor", or None)."""
    lo, _ = bounds(o)
    cx, cy = o.pose.xyz[0], o.pose.xyz[1]
    best, gap_best = None, TOUCH
    for s in scene.objects:
        if s is o or not s.collides:
            continue
        top = bounds(s)[1][2]
        gap = abs(lo[2] - top)
        R, h = _rot(s.pose.rpy), _half(s)
        dx, dy, dz = cx - s.pose.xyz[0], cy - s.pose.xyz[1], top - s.pose.xyz[2]
        local = [R[0][i] * dx + R[1][i] * dy + R[2][i] * dz for i in range(3)]
        inside = (abs(local[0]) <= h[0] + 1e-9 and abs(local[1]) <= h[1] + 1e-9) if s.geometry.box is not None \
            else math.hypot(local[0], local[1]) <= h[0] + 1e-9
        if gap <= gap_best and inside:
            best, gap_best = s.id, gap
    if best is None and abs(lo[2]) <= TOUCH:
        return "floor"
    return best


def _gap(a, b):
    (alo, ahi), (blo, bhi) = bounds(a), bounds(b)
    d = [max(0.0, alo[i] - bhi[i], blo[i] - ahi[i]) for i in (0, 1)]
    return math.hypot(*d)


def _extent(o):
    lo, hi = bounds(o)
    return max(hi[0] - lo[0], hi[1] - lo[1])


def _stacked(a, b):
    (alo, ahi), (blo, bhi) = bounds(a), bounds(b)
    return all(min(ahi[i], bhi[i]) - max(alo[i], blo[i]) > OVERLAP for i in (0, 1))


def _side_range(scene, o):
    lo, hi = bounds(o)
    vs = [lateral(scene, x, y) for x in (lo[0], hi[0]) for y in (lo[1], hi[1])]
    return min(vs), max(vs)


def related(scene, rel, o, lm) -> bool:
    if o.id == lm.id:
        return False
    if rel == "next_to":
        return not _stacked(o, lm) and _gap(o, lm) <= max(NEAR, 0.5 * max(_extent(o), _extent(lm)))
    v = lateral(scene, o.pose.xyz[0], o.pose.xyz[1])
    vmin, vmax = _side_range(scene, lm)
    return v > vmax if rel == "left_of" else v < vmin


def is_between(o, a, b) -> bool:
    if o.id in (a.id, b.id) or a.id == b.id:
        return False
    (px, py), (ax, ay), (bx, by) = o.pose.xyz[:2], a.pose.xyz[:2], b.pose.xyz[:2]
    sx, sy = bx - ax, by - ay
    length2 = sx * sx + sy * sy
    t = ((px - ax) * sx + (py - ay) * sy) / length2
    off = abs(sx * (py - ay) - sy * (px - ax)) / math.sqrt(length2)
    return 0 < t < 1 and off <= 0.5 * math.sqrt(length2)


def _dist_to_robot(scene, o):
    rx, ry, _ = robot_pose(scene)
    lo, hi = bounds(o)
    return math.hypot(min(max(rx, lo[0]), hi[0]) - rx, min(max(ry, lo[1]), hi[1]) - ry)


def _trailing(object_id: str) -> list[str]:
    return re.findall(r"[a-z]+|[0-9]+", object_id.lower())


def _named(o, d: Desc) -> bool:
    if d.id is not None:
        return o.id == d.id
    if d.type is not None and o.type != d.type:
        return False
    if d.id_num is not None:
        parts = _trailing(o.id)
        return bool(parts) and parts[-1].isdigit() and int(parts[-1]) == d.id_num
    if d.id_tail is not None:
        tail = _trailing(d.id_tail)
        parts = _trailing(o.id)
        return parts[-len(tail):] == tail
    return True


def expected(scene, d: Desc, role: str | None) -> set[str]:
    """The ids ``d`` names in ``role`` ("pick", "support", "park" or None for a landmark)."""
    if d.type == "floor":
        return {"floor"}
    kinds = {"pick": PICKABLE, "support": SUPPORTS, "park": {SPOT}, None: None}[role]
    objs = [o for o in scene.objects if (kinds is None or o.type in kinds) and _named(o, d)]
    if d.on is not None:
        marks = expected(scene, d.on, None)
        objs = [o for o in objs if support(scene, o) in marks]
    if d.not_on is not None:
        marks = expected(scene, d.not_on, None)
        objs = [o for o in objs if support(scene, o) not in marks]
    if d.rel is not None:
        marks = [o for o in scene.objects if o.id in expected(scene, d.rel[1], None)]
        kept = [o for o in objs if any(related(scene, d.rel[0], o, m) for m in marks)]
        if not kept and d.rel[0] == "next_to":  # nothing within reach: the nearest within twice the reach
            near = {}
            for o in objs:
                ok = [_gap(o, m) for m in marks if m.id != o.id and not _stacked(o, m)
                      and _gap(o, m) <= 2 * max(NEAR, 0.5 * max(_extent(o), _extent(m)))]
                if ok:
                    near[o.id] = min(ok)
            kept = [o for o in objs if o.id in near and near[o.id] <= min(near.values()) + TIE]
        objs = kept
    if d.between is not None:
        a = [o for o in scene.objects if o.id in expected(scene, d.between[0], None)]
        b = [o for o in scene.objects if o.id in expected(scene, d.between[1], None)]
        objs = [o for o in objs if any(is_between(o, x, y) for x in a for y in b)]
    if role == "park":
        objs = [o for o in objs if not o.occupied]
    if d.colour is not None:
        objs = [o for o in objs if (o.color or "").lower() == d.colour]
    if d.not_colour is not None:
        objs = [o for o in objs if (o.color or "").lower() != d.not_colour]
    if d.closest and objs:
        dist = {o.id: _dist_to_robot(scene, o) for o in objs}
        best = min(dist.values())
        objs = [o for o in objs if dist[o.id] - best <= TIE]
    if d.ordinal is not None:
        n, side = d.ordinal
        ordered = sorted(objs, key=lambda o: lateral(scene, *o.pose.xyz[:2]), reverse=side == "left")
        objs = [ordered[n - 1]] if n <= len(ordered) else []
    if d.except_colour is not None:
        objs = [o for o in objs if (o.color or "").lower() != d.except_colour]
    return {o.id for o in objs}
