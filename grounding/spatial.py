"""Spatial facts the request language refers to, computed from scene geometry.

* **support** — ``support_of(obj, scene)``: the object ``obj`` rests on. ``obj``'s
  bottom must lie within ``TOUCH_TOL`` (3 cm) of the support's top face and its
  centre over the support's footprint; the closest such face wins. An object
  resting on nothing within 3 cm of z = 0 is on the ``floor``. Only direct
  support counts (a can on a tray on a table is on the tray).
* **directions** — the robot looks along its base +x: "left" is +y and "right"
  is -y in the robot's base frame (its start pose when the scene gives no base
  pose: the car's ``car_x``, ``car_y``, ``car_qz``); "top" is +z.
* **units** — boards of one piece of furniture (shelf boards of one rack): the
  objects of one type sharing ``attributes: {unit: NAME}``, else those whose
  footprints overlap (stacked boards). "left/right shelf" compares whole units;
  "top/middle/bottom shelf" ranks boards within each unit.
* **thirds** — a relative word picks by value, not by count: over the values v
  of the compared objects (range r = max - min), the upper third
  (v >= max - r/3) is left/top/large, the lower third (v <= min + r/3) is
  right/bottom/small and the rest is middle/medium. When the spread is too
  small to tell (``SPREAD`` 5 cm, or volumes within 10 %) the word does not
  narrow anything.
"""

from __future__ import annotations

import math
from functools import lru_cache
from itertools import product

import numpy as np

from lazyground.scene.schema import PoseSpec, Scene, SceneObject

TOUCH_TOL = 0.03
SPREAD = 0.05
VOLUME_SPREAD = 1.10
FLOOR = "floor"


def world_box(obj: SceneObject) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned world bounds of the object's shape."""
    lo, hi = _box(tuple(obj.geometry.half_extents()), tuple(obj.pose.xyz), tuple(obj.pose.rpy))
    return np.array(lo), np.array(hi)


@lru_cache(maxsize=4096)
def _box(half: tuple, xyz: tuple, rpy: tuple) -> tuple[tuple, tuple]:
    """Bounds of a box of half extents ``half`` at pose (xyz, rpy); cached (requests ask the same objects again)."""
    corners = np.array(list(product(*[(-v, v) for v in half])))
    pts = PoseSpec(xyz=xyz, rpy=rpy).pose().transform_points(corners)
    return tuple(pts.min(axis=0)), tuple(pts.max(axis=0))


def _over_footprint(point: np.ndarray, support: SceneObject) -> bool:
    """Whether ``point`` (x, y) lies over the support's top face."""
    X = support.pose.pose()
    p = (np.asarray(point, float) - np.asarray(X.xyz)) @ X.rotation()
    hx, hy, _ = support.geometry.half_extents()
    if support.geometry.kind == "box":
        return abs(p[0]) <= hx + 1e-9 and abs(p[1]) <= hy + 1e-9
    return math.hypot(p[0], p[1]) <= hx + 1e-9


def support_of(obj: SceneObject, scene: Scene) -> str | None:
    """Id of the object ``obj`` rests on, ``FLOOR``, or None when it rests on nothing known."""
    lo, _ = world_box(obj)
    centre = np.asarray(obj.pose.xyz, float)
    best, best_gap = None, TOUCH_TOL
    for other in scene.objects:
        if other is obj or not other.collides:
            continue
        gap = abs(lo[2] - world_box(other)[1][2])
        if gap <= best_gap and _over_footprint(np.array([centre[0], centre[1], world_box(other)[1][2]]), other):
            best, best_gap = other.id, gap
    if best is None and abs(lo[2]) <= TOUCH_TOL:
        return FLOOR
    return best


def robot_yaw(scene: Scene) -> float:
    """The robot's heading: its base yaw, else a start heading joint (the car's ``car_qz``), else 0."""
    if scene.robot.base is not None:
        return float(scene.robot.base.rpy[2])
    yaws = [v for k, v in scene.robot.start.items() if k.endswith(("_qz", "_theta", "_yaw")) or k in ("theta", "yaw")]
    return float(yaws[0]) if yaws else 0.0


def robot_frame(point, scene: Scene) -> tuple[float, float]:
    """(ahead, left) of a world point in the robot's base frame: its base pose, else its start pose."""
    o = robot_position(scene)
    yaw = robot_yaw(scene)
    dx, dy = float(point[0]) - o[0], float(point[1]) - o[1]
    return math.cos(yaw) * dx + math.sin(yaw) * dy, -math.sin(yaw) * dx + math.cos(yaw) * dy


def lateral(obj: SceneObject, scene: Scene) -> float:
    """The object's y in the robot's base frame: larger is further left."""
    return robot_frame(obj.pose.xyz, scene)[1]


def top_height(obj: SceneObject) -> float:
    return float(world_box(obj)[1][2])


def units(objs: list[SceneObject]) -> list[list[SceneObject]]:
    """Group boards into pieces of furniture: by ``attributes.unit``, else by overlapping footprints."""
    named: dict[str, list[SceneObject]] = {}
    loose: list[list[SceneObject]] = []
    for o in objs:
        name = o.attributes.get("unit")
        if name is not None:
            named.setdefault(str(name), []).append(o)
            continue
        lo, hi = world_box(o)
        joined = [g for g in loose if any(_overlap(lo, hi, *world_box(m)) for m in g)]
        merged = [o] + [m for g in joined for m in g]
        loose = [g for g in loose if g not in joined] + [merged]
    return list(named.values()) + loose


def _overlap(lo_a, hi_a, lo_b, hi_b, eps: float = 1e-3) -> bool:
    return bool(np.all(lo_a[:2] < hi_b[:2] - eps) and np.all(lo_b[:2] < hi_a[:2] - eps))


def thirds(values: dict[str, float], spread: float) -> dict[str, str] | None:
    """Map ids to "high" / "mid" / "low" by the thirds rule; None when the spread is below ``spread``."""
    if not values:
        return {}
    vmax, vmin = max(values.values()), min(values.values())
    r = vmax - vmin
    if r < spread:
        return None
    return {k: "high" if v >= vmax - r / 3 else "low" if v <= vmin + r / 3 else "mid" for k, v in values.items()}


def extremes(values: dict[str, float], high: bool, tol: float) -> set[str]:
    """Ids whose value is within ``tol`` of the maximum (``high``) or the minimum."""
    if not values:
        return set()
    best = max(values.values()) if high else min(values.values())
    return {k for k, v in values.items() if abs(v - best) <= tol}


def robot_position(scene: Scene) -> np.ndarray:
    """Where distances are measured from: the robot's base pose, else its start (x, y) (``*_x``/``*_y`` joints)."""
    if scene.robot.base is not None:
        return np.asarray(scene.robot.base.xyz, float)
    xs = [v for k, v in scene.robot.start.items() if k.endswith("_x") or k == "x"]
    ys = [v for k, v in scene.robot.start.items() if k.endswith("_y") or k == "y"]
    return np.array([xs[0] if xs else 0.0, ys[0] if ys else 0.0, 0.0])


def distance_to_point(obj: SceneObject, p: np.ndarray) -> float:
    """Distance in the ground plane from the point to the object's bounds (0 inside)."""
    lo, hi = world_box(obj)
    return float(np.linalg.norm((np.clip(p, lo, hi) - p)[:2]))


def distance_between(a: SceneObject, b: SceneObject) -> float:
    """Ground-plane distance from ``a``'s centre to ``b``'s bounds ("the can nearest the table")."""
    return distance_to_point(b, np.asarray(a.pose.xyz, float))


def rows(objs: list[SceneObject], tol: float = 0.5) -> list[list[SceneObject]]:
    """Rows of a layout (parking spots): the same heading (mod 180 degrees), on one line across it, and no
    gap wider than 1.5 spacings between neighbours (a gap starts a new row)."""
    lines: dict[tuple, list[SceneObject]] = {}
    for o in objs:
        yaw = o.pose.rpy[2] % math.pi
        x, y = o.pose.xyz[0], o.pose.xyz[1]
        along = math.cos(yaw) * x + math.sin(yaw) * y  # the same for spots side by side
        key = next((k for k in lines if abs(k[0] - yaw) < 0.02 and abs(k[1] - along) < tol), (yaw, along))
        lines.setdefault(key, []).append(o)
    out = []
    for (yaw, _), line in lines.items():
        pos = {o.id: -math.sin(yaw) * o.pose.xyz[0] + math.cos(yaw) * o.pose.xyz[1] for o in line}
        line = sorted(line, key=lambda o: pos[o.id])
        steps = [pos[b.id] - pos[a.id] for a, b in zip(line, line[1:])]
        spacing = min(steps, default=0.0)
        row = [line[0]]
        for step, o in zip(steps, line[1:]):
            if step > 1.5 * spacing + 1e-6:
                out.append(row)
                row = []
            row.append(o)
        out.append(row)
    return out
