"""Approach clearance: can the hand back out of a region's grasp along its approach axis? (issue #33)

A standard grasp-pipeline test. For a pose region with an approach (:attr:`PoseRegion.approach`, the pre-pose's
offset in the target's axes), take a few of its poses (the centre and seeded samples), put the collision shapes of
the bodies rigid with the constrained frame (the hand, as :mod:`lazyground.drake.arm_reach` finds them; points on
their surfaces) at each pose and move them back along the approach direction by the hand's own length along it
(the spread of those points along the axis: the whole hand must leave the grasp), in ``STEP`` steps, against the
world's shapes the checker tests the hand against (:func:`lazyground.drake.reach_prior.candidate_obstacles`).
A region none of whose tested poses backs out is flagged ``blocked``: a heuristic that only orders the regions
(:class:`lazyground.planning.region_bandit.StagedBandit`), never drops one.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
from pydrake.geometry import Box, Cylinder, Sphere, Capsule

from lazyground.drake.approach_kernel import retreats
from lazyground.drake.arm_reach import rigid_bodies, solids_3d
from lazyground.geometry import rpy_to_matrix

STEP = 0.03  # m: spacing of the retreat's steps and of the points on the hand's surfaces; a point counts as in collision
# within STEP / 2 (no board thinner than a step skipped; a coarse, cheap test: it only orders regions)
SPACING = STEP
POSES = 23  # seeded samples per region, besides its centre (a side grasp's yaw: ~1/8 of its range faces out of a cubby)

_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # world -> {(regions, skip): flags}


def blocked_approaches(world, regions: tuple, skip=(), rng: np.random.Generator | None = None) -> frozenset[int]:
    """The indices of ``regions`` whose every tested pose's retreat along the approach is blocked (cached per world,
    regions and ``skip``; ``skip``: indices not tested, e.g. those the reach prior drops). Regions without an approach,
    or that are not workspace (end-effector) regions, are never flagged."""
    cache = _CACHE.setdefault(world, {})
    key = (regions, frozenset(skip))
    if key not in cache:
        rng = np.random.default_rng(0) if rng is None else rng
        hands: dict = {}
        cache[key] = frozenset(j for j, r in enumerate(regions)
                               if j not in key[1] and _blocked(world, r, hands, rng))
    return cache[key]


def _blocked(world, region, hands: dict, rng: np.random.Generator) -> bool:
    a = np.asarray(getattr(region, "approach", (0.0, 0.0, 0.0)), float)
    if getattr(region, "kind", "") != "workspace" or not np.any(a) or not world.plant.HasFrameNamed(region.frame):
        return False
    if region.frame not in hands:
        hands[region.frame] = _hand(world, region.frame)
    points, (names, solids, reach), tol = hands[region.frame]
    keep = names != region.object  # not the grasped object: the hand closes on it
    if not len(points) or not keep.any():
        return False
    d = a / np.linalg.norm(a)  # in the frame's axes (a workspace region's target is the frame)
    along = points @ d
    length = float(along.max() - along.min())  # the hand's extent along the axis: how far it must back out
    steps = np.arange(int(math.ceil(length / STEP)) + 1) * STEP
    lower, span, _ = region.unit_map()
    X_WR, X_SE = region.X_WR.matrix(), region.X_SE.matrix()
    vs = np.vstack([lower + span / 2, lower + span * rng.random((POSES, len(span)))])
    R = np.stack([X_WR[:3, :3] @ rpy_to_matrix(v[3:6]) @ X_SE[:3, :3] for v in vs])  # region.pose_in_world(v)
    t = (X_WR[:3, :3] @ vs[:, :3].T).T + X_WR[:3, 3] + R @ X_SE[:3, 3]
    p = np.einsum("kij,mj->kmi", R, points) + t[:, None, :]  # (poses, points, 3)
    dw = R @ d  # (poses, 3): each pose's retreat direction in the world
    centres, axes, half, rounding = solids
    return not retreats(np.ascontiguousarray(p), np.ascontiguousarray(dw), np.asarray(steps, float), centres, axes, half,
                        rounding, reach, np.asarray(keep, np.bool_), float(tol))


def _hand(world, frame: str) -> tuple[np.ndarray, tuple, float]:
    """(points on the surfaces of the bodies rigid with ``frame``, in its axes; (names, solids, centres, bounding
    half extents) of the world's shapes any of them is checked against; the collision tolerance: STEP / 2 + the largest body-world padding)."""
    kin, plant, drake = world.kinematics, world.plant, world.checker.drake
    F = kin.frame(frame)
    X_FW = np.linalg.inv(kin.matrix(F, world.q_full))
    inspector = drake.model().scene_graph().model_inspector()
    world_body = plant.world_body()
    statics = plant.GetCollisionGeometriesForBody(world_body)
    points, seen, solids, padding = [], set(), [], 0.0
    for body in rigid_bodies(plant, F.body(), set(world.planned)):
        X_FB = X_FW @ kin.matrix(body.body_frame(), world.q_full)
        filtered = drake.IsCollisionFilteredBetween(body, world_body)
        padding = max(padding, float(drake.GetPaddingMatrix()[int(body.index()), int(world_body.index())]))
        for g in plant.GetCollisionGeometriesForBody(body):
            local = surface_points(inspector.GetShape(g), SPACING)
            if local is None or filtered:
                continue
            X = X_FB @ inspector.GetPoseInFrame(g).GetAsMatrix4()
            points.append((X[:3, :3] @ local.T).T + X[:3, 3])
            for o in statics:
                if o not in seen and not inspector.CollisionFiltered(g, o):
                    seen.add(o)
                    name = inspector.GetName(o).split("::")[-1]
                    solids += [(name, s) for s in solids_3d(inspector.GetShape(o), inspector.GetPoseInFrame(o).GetAsMatrix4()) or []]
    names = np.array([n for n, _ in solids], dtype=object)
    stacked = (np.array([s.centre for _, s in solids], float).reshape(-1, 3),
               np.array([np.eye(3) if s.axes is None else s.axes for _, s in solids], float).reshape(-1, 3, 3),
               np.array([s.half for _, s in solids], float).reshape(-1, 3), np.array([s.rounding for _, s in solids], float))
    table = (names, stacked, np.array([s.reach() for _, s in solids], float).reshape(-1, 3))
    return (np.concatenate(points) if points else np.zeros((0, 3))), table, STEP / 2 + padding


def surface_points(shape, spacing: float) -> np.ndarray | None:
    """Points on a box's, cylinder's, sphere's or capsule's surface about its origin, at most ``spacing`` apart
    (roughly); None for other shapes (left out)."""
    if isinstance(shape, Box):
        half = np.asarray(shape.size(), float) / 2
        axes = [np.linspace(-h, h, max(2, int(math.ceil(2 * h / spacing)) + 1)) for h in half]
        g = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
        return g[np.any(np.isclose(np.abs(g), half), axis=1)]
    if isinstance(shape, (Cylinder, Capsule)):
        r, h = float(shape.radius()), shape.length() / 2
        n = max(6, int(math.ceil(2 * math.pi * r / spacing)))
        t = np.linspace(0, 2 * math.pi, n, endpoint=False)
        ring = np.stack([np.cos(t), np.sin(t)], axis=1)
        zs = np.linspace(-h, h, max(2, int(math.ceil(2 * h / spacing)) + 1))
        side = [np.column_stack([r * ring, np.full(n, z)]) for z in zs]
        caps = [np.column_stack([rho * ring, np.full(n, z)]) for rho in np.arange(0.0, r, spacing) for z in (-h, h)]
        if isinstance(shape, Capsule):
            caps = [np.column_stack([math.sin(f) * r * ring, np.full(n, s * (h + math.cos(f) * r))])
                    for f in np.linspace(0, math.pi / 2, 4) for s in (-1, 1)]
        return np.concatenate(side + caps)
    if isinstance(shape, Sphere):
        r = float(shape.radius())
        k = max(12, int(4 * math.pi * r * r / spacing ** 2))
        i = np.arange(k) + 0.5
        phi, theta = np.arccos(1 - 2 * i / k), math.pi * (1 + 5 ** 0.5) * i
        return r * np.column_stack([np.cos(theta) * np.sin(phi), np.sin(theta) * np.sin(phi), np.cos(phi)])
    return None
