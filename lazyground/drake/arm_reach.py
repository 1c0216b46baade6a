"""The reach prior of an arm: balls its hand carries, on a 3-D grid over its reach (issue #33).

A ball is the largest one inscribed in one collision shape of a body rigidly attached to the
frame a pose region constrains (no planned joint between them: the hand, the last link, the
fingers held still). For a pose region, the ball's centre over every pose of the region lies in
a box (:func:`lazyground.planning.reach_prior.pose_centre_box`); if no cell of that box lies in
the component of the start's ball centre, no configuration of the region is reachable
(:mod:`lazyground.planning.reach_prior`). Each ball decides alone: a region one ball cannot
reach is dropped.

The obstacles are the world's shapes Drake checks against the ball's shape (boxes, spheres,
capsules, half-spaces exactly; a cylinder by a box and a capsule inside it; meshes, convex
shapes and ellipsoids left out, which only frees cells). The grid covers where the ball centre
can be: within the chain's stretched length of the first moving joint's origin (a segment if that
joint is prismatic; later revolute and ball joints keep their origins, a prismatic one adds its
longest travel, fixed offsets their length), so a region beyond it is dropped too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Ellipsoid, HalfSpace, Sphere
from pydrake.multibody.tree import BallRpyJoint, PrismaticJoint, RevoluteJoint, WeldJoint

from lazyground.drake.chain import joints_to_world
from lazyground.drake.reach_prior import candidate_obstacles
from lazyground.drake.solids import FAR
from lazyground.planning.reach_prior import ReachGrid, Solid, placed_boxes, reach_grid, turned_point_box
from lazyground.planning.stop import default_clock
from lazyground.regions.table import pose_table
from lazyground.robots.end_effector import frame_of

CELLS_PER_RADIUS = 2  # cell side = radius / 2: a blocked shell separates at any thickness (2 rho >= cell sqrt 3)
MAX_CELLS = 12_000_000  # a larger reach gets coarser cells (a ball whose blocking radius then vanishes is skipped)
MIN_BALL = 0.025  # m: smaller balls are not used (their cells would be too many)
MAX_BALLS = 2  # per frame, nearest the frame first


@dataclass(frozen=True)
class Ball:
    """A ball in ``body`` (centre ``p_B`` in its frame, radius with the padding) and its grid from the start."""

    body: str
    p_B: tuple[float, float, float]
    radius: float
    grid: ReachGrid | None  # None: no cell blocks for it (too coarse)
    start: frozenset[int]  # the components of the start's ball centre (empty: keeps everything)
    reach: tuple = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0), math.inf)  # (a, b, radius): the centre stays that near a-b
    left_out: tuple[str, ...] = ()
    build_s: float = 0.0

    def beyond_reach(self, lower, upper) -> bool:
        """Whether the box [lower, upper] lies wholly beyond the reach (checked at 101 points of the segment, each
        with the radius widened by half their spacing)."""
        a, b, radius = np.asarray(self.reach[0]), np.asarray(self.reach[1]), self.reach[2]
        points = a + np.linspace(0.0, 1.0, 101)[:, None] * (b - a)
        gap = np.linalg.norm(np.clip(points, lower, upper) - points, axis=1)
        return bool(np.all(gap > radius + np.linalg.norm(b - a) / 200))

    def reaches(self, lower, upper) -> np.ndarray:
        """Whether some cell of each box [lower[i], upper[i]] (m, 3) of ball centres lies in the start's component."""
        if self.grid is None or not self.start:
            return np.ones(len(lower), bool)
        return self.grid.meets(lower, upper, self.start)


class ArmReach:
    """The reach prior of a world's arm, its balls built per frame on first use (cached in the world)."""

    def __init__(self, world):
        self.world = world
        self._balls: dict[str, list[tuple[Ball, np.ndarray]]] = {}  # frame -> [(ball, its centre in the frame)]
        self._built: dict[str, Ball] = {}  # body -> its ball (shared by the frames it is rigid with)
        self._pairs = None  # SceneGraph's collision candidates, listed once
        self._kept: dict[tuple, bool] = {}  # keeps' answers by the region's numbers

    @property
    def build_s(self) -> float:
        return sum(b.build_s for b in self._built.values())

    @property
    def grids(self) -> list[ReachGrid]:
        """The grids built so far."""
        return [b.grid for b in self._built.values() if b.grid is not None]

    @property
    def left_out(self) -> tuple[str, ...]:
        return tuple(dict.fromkeys(n for b in self._built.values() for n in b.left_out))

    def balls(self, frame: str) -> list[tuple[Ball, np.ndarray]]:
        """The balls rigid with ``frame`` and their centres in it, nearest first (built on first use)."""
        if frame not in self._balls:
            self._balls[frame] = [(self._ball(body, p_B, r), p_F) for body, p_B, r, p_F in _candidate_balls(self.world, frame)]
        return self._balls[frame]

    def _ball(self, body, p_B, r) -> Ball:
        if body.name() not in self._built:
            if self._pairs is None:
                self._pairs = self.world.checker.drake.model().scene_graph().model_inspector().GetCollisionCandidates()
            self._built[body.name()] = _build_ball(self.world, body, p_B, r, self._pairs)
        return self._built[body.name()]

    def keeps(self, region) -> bool:
        """Whether ``region`` may be reached (:meth:`keeps_all` of it alone)."""
        return self.keeps_all((region,))[0]

    def keeps_all(self, regions) -> list[bool]:
        """Whether each of ``regions`` may be reached: False only for a pose region for one ball of which no cell of
        the box of its centres over the region's poses lies in the start's component. Other regions are kept.
        The boxes of all regions at once, each turned point's box once per shape of region (frame, X_ST, angles)."""
        out = [True] * len(regions)
        poses = [j for j, region in enumerate(regions) if hasattr(region, "X_WR")]
        if not poses:
            return out
        table = pose_table(regions if len(poses) == len(regions) else tuple(regions[j] for j in poses),
                           getattr(self.world, "attached", None))
        # a request builds its regions anew: the same numbers give the same answer (#31: ~13 ms a Fetch request)
        numbers = np.concatenate([table.X_WR.reshape(len(poses), 16), table.X_ST.reshape(len(poses), 16), table.lower, table.span], axis=1)
        todo: dict[str, list[int]] = {}  # frame -> the table's rows to compute
        keys = [(frame, row.tobytes()) for frame, row in zip(table.frames, numbers)]
        for i, (j, key) in enumerate(zip(poses, keys)):
            if key in self._kept:
                out[j] = self._kept[key]
            else:
                todo.setdefault(key[0], []).append(i)
        for frame, rows in todo.items():
            X_WR, X_ST, lower, span = (a[rows] for a in (table.X_WR, table.X_ST, table.lower, table.span))
            kept = np.ones(len(rows), bool)
            shapes = [r.tobytes() for r in np.concatenate([X_ST.reshape(len(rows), 16), lower[:, 3:], span[:, 3:]], axis=1)]  # X_ST and angles
            for ball, p_T in self.balls(frame):
                left = np.flatnonzero(kept)  # a region one ball cannot reach is dropped: the next ball only tests the rest
                if not len(left):
                    break
                turned = {}  # shape -> the turned point's box
                for i in left.tolist():
                    if shapes[i] not in turned:
                        turned[shapes[i]] = turned_point_box(X_ST[i], p_T, lower[i], span[i])
                boxes = [turned[shapes[i]] for i in left.tolist()]
                lo, hi = placed_boxes(np.array([b[0] for b in boxes]).reshape(-1, 3), np.array([b[1] for b in boxes]).reshape(-1, 3),
                                      lower[left], span[left], X_WR[left])
                kept[left] = ball.reaches(lo, hi)
            for i, k in zip(rows, kept.tolist()):
                out[poses[i]] = self._kept[keys[i]] = k
        return out

    def centres(self, frame: str, qs) -> np.ndarray:
        """The centres (m, balls, 3) of ``frame``'s balls at planned configurations ``qs`` (m, dim)."""
        kin, world = self.world.kinematics, self.world
        F = kin.frame(frame)
        out = []
        for q in np.atleast_2d(qs):
            X = kin.matrix(F, world.full(q))
            out.append([X[:3, :3] @ p + X[:3, 3] for _, p in self.balls(frame)])
        return np.array(out).reshape(len(out), len(self.balls(frame)), 3)


def end_effector_frame(world) -> str | None:
    """The name of ``world``'s robot's end-effector frame (:func:`lazyground.robots.end_effector.frame_of`), or None
    when it has none in the plant (a car, or an invalid robot.yaml beside the model)."""
    try:
        frame = frame_of(world.scene.robot)
    except ValueError:  # a SceneError: the robot.yaml beside the model is invalid
        return None
    return frame if frame and world.plant.HasFrameNamed(frame) else None


def arm_reach(world) -> ArmReach | None:
    """The reach prior of ``world``'s arm, or None when its end effector has no ball (none large enough, or a joint
    on the way to the world that the reach bound does not handle)."""
    frame = end_effector_frame(world)
    if frame is None:
        return None
    prior = ArmReach(world)
    return prior if prior.balls(frame) else None  # the end effector's grids built now


def _candidate_balls(world, frame: str) -> list:
    """(body, centre in body, radius, centre in the frame) of the largest ball of each body rigid with ``frame``,
    at least MIN_BALL, nearest the frame first, at most MAX_BALLS; none when the chain has a joint _reach cannot bound."""
    kin, plant = world.kinematics, world.plant
    F = kin.frame(frame)
    X_FW = np.linalg.inv(kin.matrix(F, world.q_full))
    inspector = world.checker.drake.model().scene_graph().model_inspector()
    out = []
    for body in rigid_bodies(plant, F.body(), set(world.planned)):
        best = None
        for g in plant.GetCollisionGeometriesForBody(body):
            inscribed = _inscribed(inspector.GetShape(g))
            if inscribed is not None and (best is None or inscribed > best[1]):
                best = (inspector.GetPoseInFrame(g).translation(), inscribed, g)
        if best is None or best[1] < MIN_BALL or _reach(world, body, best[0]) is None:
            continue
        X_WB = kin.matrix(body.body_frame(), world.q_full)
        p_F = (X_FW @ X_WB @ np.append(best[0], 1.0))[:3]
        out.append((body, tuple(float(x) for x in best[0]), best[1], p_F))
    out.sort(key=lambda b: float(np.linalg.norm(b[3])))
    return out[:MAX_BALLS]


def rigid_bodies(plant, body, planned: set[int]) -> list:
    """The bodies joined to ``body`` by joints none of whose positions is planned (welds, held joints)."""
    joints = [plant.get_joint(j) for j in plant.GetJointIndices()]
    seen, todo = {int(body.index()): body}, [body]
    while todo:
        b = todo.pop()
        for j in joints:
            if any(j.position_start() + k in planned for k in range(j.num_positions())):
                continue
            for near, far in ((j.parent_body(), j.child_body()), (j.child_body(), j.parent_body())):
                if near.index() == b.index() and int(far.index()) not in seen and far.index() != plant.world_body().index():
                    seen[int(far.index())] = far
                    todo.append(far)
    return list(seen.values())


def _inscribed(shape) -> float | None:
    """The radius of the largest ball about the shape's origin inside it, or None."""
    if isinstance(shape, Box):
        return float(min(shape.size())) / 2
    if isinstance(shape, (Sphere, Capsule)):
        return float(shape.radius())
    if isinstance(shape, Cylinder):
        return float(min(shape.radius(), shape.length() / 2))
    if isinstance(shape, Ellipsoid):
        return float(min(shape.a(), shape.b(), shape.c()))
    return None


def _reach(world, body, p_B) -> tuple[np.ndarray, np.ndarray, float] | None:
    """(a, b, length): the point ``p_B`` of ``body`` stays within ``length`` of the segment a-b in the world, the
    positions the chain's first moving joint's origin takes (a prismatic joint's travel; a = b for a revolute or ball
    joint); each later joint adds its fixed offset, a prismatic one its longest travel. None when a joint on the way
    is not revolute, prismatic, ball or welded, or nothing moves the body."""
    planned, space = list(world.planned), world.space
    a = b = prev = None
    length = 0.0
    for j in joints_to_world(world.plant, body)[::-1]:  # from the world down
        if isinstance(j, PrismaticJoint):
            i = j.position_start()
            travel = (space.lower[planned.index(i)], space.upper[planned.index(i)]) if i in planned else (world.q_full[i],) * 2
        elif not isinstance(j, (WeldJoint, RevoluteJoint, BallRpyJoint)):
            return None
        if prev is None and isinstance(j, WeldJoint):
            continue  # still fixed in the world
        if prev is None:  # the first moving joint: its parent frame is fixed in the world
            X_WF = world.kinematics.matrix(j.frame_on_parent(), world.q_full)
            a = b = X_WF[:3, 3]
            if isinstance(j, PrismaticJoint):
                axis = X_WF[:3, :3] @ np.asarray(j.translation_axis(), float)
                a, b = X_WF[:3, 3] + travel[0] * axis, X_WF[:3, 3] + travel[1] * axis
        else:  # the previous joint's child frame to this one's parent frame, fixed in the body between them
            length += float(np.linalg.norm(j.frame_on_parent().GetFixedPoseInBodyFrame().translation()
                                           - prev.frame_on_child().GetFixedPoseInBodyFrame().translation()))
            if isinstance(j, WeldJoint):
                length += float(np.linalg.norm(j.X_FM().translation()))
            elif isinstance(j, PrismaticJoint):
                length += max(abs(float(t)) for t in travel)
        prev = j
    if prev is None:
        return None
    length += float(np.linalg.norm(np.asarray(p_B) - prev.frame_on_child().GetFixedPoseInBodyFrame().translation()))
    return a, b, length


def _build_ball(world, body, p_B, radius: float, pairs=None) -> Ball:
    """The grid of ``body``'s ball (centre ``p_B``) among the world's shapes it is checked against."""
    t0 = default_clock()
    drake = world.checker.drake
    inspector = drake.model().scene_graph().model_inspector()
    g_ball = max(world.plant.GetCollisionGeometriesForBody(body), key=lambda g: _inscribed(inspector.GetShape(g)) or -1.0)
    obstacles, padding = candidate_obstacles(world, body, g_ball, pairs)
    solids, left_out = [], []
    for g in obstacles:
        s = solids_3d(inspector.GetShape(g), inspector.GetPoseInFrame(g).GetAsMatrix4())
        if s is None:
            left_out.append(inspector.GetName(g))
        else:
            solids += s
    r = radius + padding
    a, b, length = _reach(world, body, p_B)
    lower, upper = np.minimum(a, b) - length, np.maximum(a, b) + length
    cell = max(r / CELLS_PER_RADIUS, (float(np.prod(upper - lower)) / MAX_CELLS) ** (1 / 3))
    grid = reach_grid(lower, upper, r, solids, cell, bounded=True, reach=(a, b, length)) if r > cell * math.sqrt(3) / 2 else None
    start = frozenset()
    if grid is not None:
        X = world.kinematics.matrix(body.body_frame(), world.q_full)
        c = X[:3, :3] @ np.asarray(p_B) + X[:3, 3]
        start = frozenset(grid.components(c - 1e-9, c + 1e-9))
        grid.count_table(start)  # (keeps_all's lookups: built now, as set-up)
    return Ball(body.name(), tuple(p_B), r, grid, start, (tuple(a), tuple(b), length), tuple(left_out), default_clock() - t0)


def solids_3d(shape, X_WG: np.ndarray) -> list[Solid] | None:
    """Solids inside the shape at world pose ``X_WG`` (a cylinder: a box and a capsule inside it), or None when the
    shape has none here (a mesh, a convex shape, an ellipsoid: left out)."""
    R, p = X_WG[:3, :3], X_WG[:3, 3]
    axes = tuple(map(tuple, R))
    if isinstance(shape, Box):
        return [Solid(tuple(p), tuple(np.asarray(shape.size(), float) / 2), 0.0, axes)]
    if isinstance(shape, Sphere):
        return [Solid(tuple(p), (0.0, 0.0, 0.0), float(shape.radius()))]
    if isinstance(shape, Capsule):
        return [Solid(tuple(p), (0.0, 0.0, shape.length() / 2), float(shape.radius()), axes)]
    if isinstance(shape, Cylinder):
        r, h = float(shape.radius()), shape.length() / 2
        rho = min(r, h)
        return [Solid(tuple(p), (r / math.sqrt(2), r / math.sqrt(2), h), 0.0, axes),
                Solid(tuple(p), (0.0, 0.0, h - rho), rho, axes)]
    if isinstance(shape, HalfSpace):  # z <= 0 in its frame: a box FAR deep under it
        return [Solid(tuple(p - R[:, 2] * FAR), (FAR, FAR, FAR), 0.0, axes)]
    return None
