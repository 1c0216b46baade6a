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
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Cylinder, Sphere, Capsule

from lazyground.drake.approach_kernel import retreats
from lazyground.drake.arm_reach import end_effector_frame, rigid_bodies, solids_3d
from lazyground.geometry import pose_matrices, rpy_to_matrices
from lazyground.regions.base import unit_maps

STEP = 0.03  # m: spacing of the retreat's steps and of the points on the hand's surfaces; a point counts as in collision
# within STEP / 2 (no board thinner than a step skipped; a coarse, cheap test: it only orders regions)
SPACING = STEP
POSES = 23  # seeded samples per region, besides its centre (a side grasp's yaw: ~1/8 of its range faces out of a cubby)

_CACHE: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # world -> {(regions, skip): flags}
_HANDS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # world -> {frame: Hand}


@dataclass(frozen=True)
class Hand:
    """A frame's hand in a world: points on the surfaces of the bodies rigid with the frame (in its axes), the world's
    shapes any of them is checked against (stacked solids, each solid's owner: an index into ``names``, the owning
    shape's name) and the collision tolerance (STEP / 2 + the largest body-world padding)."""

    points: np.ndarray
    names: dict[str, int]
    owners: np.ndarray  # (solids,) int
    solids: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # centres, axes, half extents, roundings
    reach: np.ndarray  # (solids, 3): their bounding half extents
    tol: float


def blocked_approaches(world, regions: tuple, skip=(), rng: np.random.Generator | None = None) -> frozenset[int]:
    """The indices of ``regions`` whose every tested pose's retreat along the approach is blocked (cached per world,
    by the tested regions' numbers and ``skip``; ``skip``: indices not tested, e.g. those the reach prior drops).
    Regions without an approach, or that are not workspace (end-effector) regions, are never flagged. The poses are
    drawn region by region in order (one ``rng.random`` for all: the same numbers); all regions of a frame are tested
    in one compiled call."""
    skip = frozenset(skip)
    tested = _tested(world, regions, skip)  # [(index, frame, owner)]
    if not tested:
        return frozenset()
    rows = [regions[j] for j, _, _ in tested]
    X_WR, X_SE = pose_matrices([r.X_WR for r in rows]), pose_matrices([r.X_SE for r in rows])
    lower, span, _ = unit_maps(rows)
    approach = np.array([r.approach for r in rows], float)
    # what the flags depend on (hashing 256 regions' dataclasses cost ~1 ms a look-up, #33)
    key = (skip, tuple(tested), b"".join(x.tobytes() for x in (X_WR, X_SE, lower, span, approach)))
    cache = _CACHE.setdefault(world, {})
    flags = cache.get(key)
    if flags is None:
        rng = np.random.default_rng(0) if rng is None else rng
        vs = np.empty((len(rows), POSES + 1, span.shape[1]))  # per region: the centre and seeded samples
        vs[:, 0] = lower + span / 2
        vs[:, 1:] = lower[:, None] + span[:, None] * rng.random((len(rows) * POSES, span.shape[1])).reshape(len(rows), POSES, -1)
        d, steps = _retreat(world, tested, approach)
        frames = np.array([f for _, f, _ in tested], dtype=object)
        index, owners = np.array([j for j, _, _ in tested]), np.array([o for _, _, o in tested], np.int64)
        flags = set()
        for frame in dict.fromkeys(f for _, f, _ in tested):
            k = np.flatnonzero(frames == frame)
            flags.update(index[k][_blocked(hand(world, frame), d[k], steps[k], X_WR[k], X_SE[k], vs[k], owners[k])].tolist())
        flags = cache[key] = frozenset(flags)
    return flags


def _tested(world, regions, skip: frozenset) -> list[tuple[int, str, int]]:
    """(index, frame, owner) of the regions tested, in order: workspace regions with an approach, not in ``skip``,
    whose frame is in the plant and has a hand with points and a solid not the grasped object's (owner: that object's
    index in the hand's names, or -1)."""
    out, frame_ok, owner_ok = [], {}, {}
    for j, region in enumerate(regions):
        if j in skip or getattr(region, "kind", "") != "workspace" or not any(getattr(region, "approach", ())):
            continue
        frame = region.frame
        if frame not in frame_ok:
            frame_ok[frame] = world.plant.HasFrameNamed(frame) and len(hand(world, frame).points) > 0
        if not frame_ok[frame]:
            continue
        h = hand(world, frame)
        owner = h.names.get(region.object, -1)  # not the grasped object: the hand closes on it
        if (frame, owner) not in owner_ok:
            owner_ok[frame, owner] = bool(np.any(h.owners != owner))
        if owner_ok[frame, owner]:
            out.append((j, frame, owner))
    return out


def _retreat(world, tested, approach: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per tested region: the approach's direction (in the frame's axes: a workspace region's target is the frame) and
    the retreat's steps (the hand's extent along it, how far it must back out, over STEP), once per frame and approach."""
    d, steps, done = np.empty((len(tested), 3)), np.empty(len(tested), np.int64), {}
    for i, ((_, frame, _), a) in enumerate(zip(tested, approach)):
        key = (frame, a.tobytes())
        if key not in done:
            u = a / np.linalg.norm(a)
            along = hand(world, frame).points @ u
            done[key] = u, int(math.ceil(float(along.max() - along.min()) / STEP)) + 1
        d[i], steps[i] = done[key]
    return d, steps


def _blocked(h: Hand, d, steps, X_WR, X_SE, vs, owners) -> np.ndarray:
    """Whether each tested region (one frame's: directions ``d``, steps, X_WR, X_SE, poses ``vs``, owners) has no
    pose that backs out."""
    R = X_WR[:, None, :3, :3] @ rpy_to_matrices(vs[..., 3:6].reshape(-1, 3)).reshape(vs.shape[:2] + (3, 3)) \
        @ X_SE[:, None, :3, :3]  # (regions, poses, 3, 3): region.pose_in_world(v)
    t = (X_WR[:, :3, :3] @ vs[..., :3].transpose(0, 2, 1)).transpose(0, 2, 1) + X_WR[:, None, :3, 3] \
        + (R @ X_SE[:, None, :3, 3, None])[..., 0]
    dw = (R @ d[:, None, :, None])[..., 0]  # (regions, poses, 3): each pose's retreat direction in the world
    free = retreats(np.ascontiguousarray(R), np.ascontiguousarray(t), np.ascontiguousarray(h.points, float),
                    np.ascontiguousarray(dw), steps, STEP, *h.solids, h.reach, h.owners, owners, float(h.tol))
    return ~np.asarray(free, bool)


def hand(world, frame: str) -> Hand:
    """``frame``'s :class:`Hand` in ``world`` (built once per world and frame: the world's set-up builds its end
    effector's, :func:`warm_hand`)."""
    hands = _HANDS.setdefault(world, {})
    if frame not in hands:
        hands[frame] = _hand(world, frame)
    return hands[frame]


def warm_hand(world) -> None:
    """Build ``world``'s end effector's :class:`Hand` now (set-up), when its robot has one."""
    frame = end_effector_frame(world)
    if frame is not None:
        hand(world, frame)


def _hand(world, frame: str) -> Hand:
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
    names = {n: i for i, n in enumerate(dict.fromkeys(n for n, _ in solids))}
    stacked = (np.array([s.centre for _, s in solids], float).reshape(-1, 3),
               np.array([np.eye(3) if s.axes is None else s.axes for _, s in solids], float).reshape(-1, 3, 3),
               np.array([s.half for _, s in solids], float).reshape(-1, 3), np.array([s.rounding for _, s in solids], float))
    return Hand(np.concatenate(points) if points else np.zeros((0, 3)), names,
                np.array([names[n] for n, _ in solids], np.int64), stacked,
                np.array([s.reach() for _, s in solids], float).reshape(-1, 3), STEP / 2 + padding)


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
