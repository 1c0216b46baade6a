"""Reject an IK target by the hand alone, before any solve (#19).

The bodies rigid with the end-effector frame (on Fetch the palm, the fingers and
the wrist-roll link) sit at a pose the target fixes, whatever arm configuration
IK finds. When one of them, placed at the target, lies in an obstacle, every
answer collides: on fetch_boxes_3 that was the cause of ~55 % of the attempts
that failed "in collision", each of which had paid a batch solve, a pre-pose
solve and up to three collision checks.

The test is sound, i.e. it rejects no target for which Drake's checker would
accept an IK answer: probe points lie inside the hand's collision shapes, and for
a convex obstacle S and any point p of a shape A, signed_distance(A, S) <=
signed_distance(p, S). An accepted answer puts the frame within
``accepted_error`` of the target, which moves a point at distance r from the
frame's origin by at most dp + r * angle; a target is rejected only when a point,
so moved, would still be closer than the pair's padding (less PROBE_SLACK). Only
geometry pairs the checker checks count (SceneGraph's collision candidates the
checker does not filter), and only obstacles on anchored bodies whose solid
(:mod:`lazyground.drake.solids`) is exact; others are never a reason to reject.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, HalfSpace, Role, Sphere

from lazyground.drake import compiled
from lazyground.drake.arm_reach import rigid_bodies
from lazyground.drake.ik import kernels
from lazyground.drake.solids import solid

PROBE_SLACK = 1e-4  # m: Drake's distances are exact to far less; kept off the padding boundary
_GRID = (-1.0, 0.0, 1.0)
EXACT = (Box, Cylinder, Capsule, Sphere, HalfSpace)  # obstacle shapes whose solid's signed distance is exact
_PROBES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # world -> {(frame, dp, angle): probe}


@dataclass(frozen=True)
class Obstacles:
    """The obstacles as solids (:mod:`lazyground.drake.solids`) and, per probe point, the distance below which it collides."""

    R_WS: np.ndarray  # (K, 3, 3)
    p_WS: np.ndarray  # (K, 3): the solids' centres
    half: np.ndarray  # (K, 3)
    rounding: np.ndarray  # (K,)
    cylinder: np.ndarray  # (K,) bool
    limit: np.ndarray  # (K, P): reject when a point's signed distance is below this (-inf: the pair is not checked)
    near: np.ndarray  # (K,): the hand's origin farther than this from the obstacle, no probe point can reject


@dataclass(frozen=True)
class HandProbe:
    """Points inside the hand (in the end-effector frame) and the obstacles they are tested against."""

    points: np.ndarray  # (P, 3)
    obstacles: Obstacles | None

    def blocked(self, X_WT: np.ndarray) -> np.ndarray:
        """Whether every IK answer for each target pose (B, 4, 4) of the frame collides, by the hand alone."""
        X_WT = np.ascontiguousarray(X_WT, float).reshape(-1, 4, 4)
        out = np.zeros(len(X_WT), bool)
        obs = self.obstacles
        if obs is None or not len(self.points):
            return out
        kernels.probe_rows(X_WT, self.points, obs.R_WS, obs.p_WS, obs.half, obs.rounding, obs.cylinder, obs.limit, obs.near, out)
        return out


def hand_probe(world, frame: str, max_dp: float, max_angle: float) -> HandProbe:
    """The probe of ``frame`` in ``world`` for answers within ``max_dp`` (m) and ``max_angle`` (rad) of their target
    (built once per world and arguments: ~10 ms, against a goal source per plan)."""
    probes = _PROBES.setdefault(world, {})
    key = (frame, max_dp, max_angle)
    if key not in probes:
        compiled.warm_up()  # its test is compiled (lazyground.drake.ik.kernels): once per process, not a request's time
        probes[key] = _build(world, frame, max_dp, max_angle)
    return probes[key]


def _build(world, frame: str, max_dp: float, max_angle: float) -> HandProbe:
    checker, plant = world.checker.drake, world.plant
    inspector = checker.model().scene_graph().model_inspector()
    kin = world.kinematics
    E = kin.frame(frame)
    X_EW = kin.X_WF(E, world.q_full).inverse()
    rigid = {int(b.index()) for b in rigid_bodies(plant, E.body(), set(int(i) for i in world.planned))
             if b.model_instance() == world.robot}  # a held object's shapes are not the hand's
    body_of = {g: plant.GetBodyFromFrameId(inspector.GetFrameId(g)) for g in inspector.GetAllGeometryIds(Role.kProximity)}
    hands = [g for g, body in body_of.items() if body is not None and int(body.index()) in rigid]
    points, owners, radii = [], [], []  # probe points in E, the hand geometry (its index in hands) each lies in, the ball radius around it
    for h, g in enumerate(hands):
        X_EG = (X_EW @ kin.X_WF(body_of[g].body_frame(), world.q_full) @ inspector.GetPoseInFrame(g)).GetAsMatrix4()
        for p, rho in _probe_balls(inspector.GetShape(g)):
            points.append(X_EG[:3, :3] @ p + X_EG[:3, 3])
            owners.append(h)
            radii.append(rho)
    points, owners, radii = np.array(points).reshape(-1, 3), np.array(owners, int), np.array(radii)
    moved = max_dp + max_angle * np.linalg.norm(points, axis=1) + PROBE_SLACK  # how far an answer may move each point
    rows = []
    context = plant.CreateDefaultContext()  # obstacles are anchored: any context has their pose
    for g_env, env in body_of.items():  # the pairs the checker checks: not filtered in SceneGraph nor by the checker
        if env is None or checker.IsPartOfRobot(env) or not plant.IsAnchored(env):
            continue
        pairs = [(h, g) for h, g in enumerate(hands) if not inspector.CollisionFiltered(g, g_env)
                 and not checker.IsCollisionFilteredBetween(body_of[g], env)]
        shape = inspector.GetShape(g_env)
        if not pairs or not isinstance(shape, EXACT):
            continue  # a mesh or ellipsoid: its solid is the box around it, whose distance is no upper bound
        X_WS = (plant.EvalBodyPoseInWorld(context, env) @ inspector.GetPoseInFrame(g_env)).GetAsMatrix4()
        centre, half, rounding, cylinder = solid(shape)
        padding = np.full(len(hands), -np.inf)
        for h, g in pairs:
            padding[h] = checker.GetPaddingBetween(body_of[g], env)
        limit = padding[owners] - moved + radii
        rows.append((X_WS[:3, :3], X_WS[:3, :3] @ centre + X_WS[:3, 3], half, rounding, cylinder, limit))
    if not rows:
        return HandProbe(points, None)
    R, p, half, rounding, cylinder, limit = (np.array(column) for column in zip(*rows))
    reach = np.max(np.where(np.isfinite(limit), limit, 0.0), axis=1, initial=0.0)  # a point this far out may still reject
    hand = float(np.max(np.linalg.norm(points, axis=1), initial=0.0))
    return HandProbe(points, Obstacles(R, p, half, rounding, cylinder.astype(bool), limit, hand + np.maximum(reach, 0.0)))


def _probe_balls(shape) -> list[tuple[np.ndarray, float]]:
    """Balls (centre in the geometry's frame, radius) inside a shape: a 3x3x3 grid over a box or cylinder
    (corners, edge and face middles, centre; on a cylinder the rim at eight angles), a sphere or capsule's core."""
    if isinstance(shape, Box):
        h = np.asarray(shape.size()) / 2
        return [(np.array([a, b, c]) * h, 0.0) for a in _GRID for b in _GRID for c in _GRID]
    if isinstance(shape, Cylinder):
        r, L = shape.radius(), shape.length() / 2
        rim = [np.zeros(2)] + [r * np.array([np.cos(t), np.sin(t)]) for t in np.arange(8) * np.pi / 4]
        return [(np.array([x, y, c * L]), 0.0) for x, y in rim for c in _GRID]
    if isinstance(shape, Sphere):
        return [(np.zeros(3), shape.radius())]
    if isinstance(shape, Capsule):
        return [(np.array([0.0, 0.0, c * shape.length() / 2]), shape.radius()) for c in _GRID]
    return []
