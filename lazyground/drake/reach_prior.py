"""The reach prior of a world's planar robot (a car): its disc and the obstacles across its height (issue #33).

The robot's disc is the largest vertical cylinder held by one collision shape of the body a
planar joint moves (a box standing upright: the disc inscribed in its footprint, over its
height). The obstacles are the environment's shapes that Drake checks against that shape and that
reach into the cylinder's height, as seen from above: a box or cylinder standing upright is its
footprint, a sphere or an upright capsule the widest disc it has within that height. Anything
else (a tilted box or cylinder, a mesh, a half-space) is left out, which only frees cells, so
the prior stays sound (:mod:`lazyground.planning.reach_prior`).
"""

from __future__ import annotations

import math

import numpy as np
from pydrake.geometry import Box, Capsule, Cylinder, Sphere
from pydrake.multibody.tree import PlanarJoint

from lazyground.planning.reach_prior import PlanarReach, Solid, reach_grid
from lazyground.planning.stop import default_clock

CELLS_PER_RADIUS = 8  # cell side = radius / 8: the blocking radius is 91 % of the disc's (a car: 0.82 of 0.9 m)
MAX_CELLS = 20_000_000  # a larger area gets coarser cells
BAND_MARGIN = 1e-3  # m: heights within this of the cylinder's ends are not counted (the body's surface)
TILT = 1e-6  # sine of the largest tilt from upright still taken as upright (the footprint shrinks by it)


def planar_reach(world) -> PlanarReach | None:
    """The reach prior of ``world`` (a DrakeWorld) for its start, or None when the robot is not a planar
    one this module understands (one PlanarJoint from the world, its three positions planned, its frames
    the identity) or holds no upright disc."""
    t0 = default_clock()
    drake, plant = world.checker.drake, world.plant
    joint = _planar_joint(plant, world.robot)
    if joint is None:
        return None
    starts = [joint.position_start() + k for k in range(3)]
    planned = list(world.coordinates.planned)
    if any(p not in planned for p in starts):
        return None
    index = tuple(planned.index(p) for p in starts)
    inspector = drake.model().scene_graph().model_inspector()
    body = joint.child_body()
    disc = _disc(inspector, plant.GetCollisionGeometriesForBody(body))
    if disc is None:
        return None
    g_robot, radius, offset, (z0, z1) = disc
    obstacles, padding = candidate_obstacles(world, body, g_robot)
    solids, left_out = [], []
    for g in obstacles:
        s = footprint(inspector.GetShape(g), inspector.GetPoseInFrame(g).GetAsMatrix4(), z0 + BAND_MARGIN, z1 - BAND_MARGIN)
        if s is False:
            left_out.append(inspector.GetName(g))
        elif s is not None:
            solids.append(s)
    space = world.space
    # the planner holds every configuration it checks to the limits (motion_validator.samples_free), so the disc
    # centre stays within them, widened by the disc's offset from the body frame
    reach = float(np.hypot(*offset))
    lower = np.array([space.lower[index[0]], space.lower[index[1]]]) - reach
    upper = np.array([space.upper[index[0]], space.upper[index[1]]]) + reach
    r = radius + padding
    cell = max(r / CELLS_PER_RADIUS, math.sqrt(float(np.prod(upper - lower)) / MAX_CELLS))
    grid = reach_grid(lower, upper, r, solids, cell, bounded=True)
    prior = PlanarReach(grid, frozenset(), index, offset, tuple(left_out))
    c = prior.centres(world.start)[0]
    start = frozenset(grid.components(c - 1e-9, c + 1e-9))
    grid.count_table(start)  # (keeps_all's lookups: built now, as set-up)
    return PlanarReach(grid, start, index, offset, tuple(left_out), default_clock() - t0)


def candidate_obstacles(world, body, g_robot, pairs=None) -> tuple[list, float]:
    """(the world body's geometries Drake checks against the robot's geometry ``g_robot`` of ``body``, the padding
    between the body and the world): none when the checker filters the pair of bodies. ``pairs``: SceneGraph's
    collision candidates, if the caller has them (a 64-can rack has ~10,000: 0.3 s to list)."""
    drake, plant = world.checker.drake, world.plant
    inspector = drake.model().scene_graph().model_inspector()
    pairs = inspector.GetCollisionCandidates() if pairs is None else pairs
    candidates = {b if a == g_robot else a for a, b in pairs if g_robot in (a, b)}
    world_body = plant.world_body()
    padding = float(drake.GetPaddingMatrix()[int(body.index()), int(world_body.index())])
    if drake.IsCollisionFilteredBetween(body, world_body):
        return [], padding
    return [g for g in plant.GetCollisionGeometriesForBody(world_body) if g in candidates], padding


def _planar_joint(plant, robot):
    """The robot's planar joint from the world with identity frames, or None."""
    joints = [plant.get_joint(j) for j in plant.GetJointIndices(robot)]
    planar = [j for j in joints if isinstance(j, PlanarJoint)]
    if len(planar) != 1:
        return None
    j = planar[0]
    if j.parent_body().index() != plant.world_body().index():
        return None
    context = plant.CreateDefaultContext()
    for frame in (j.frame_on_parent(), j.frame_on_child()):
        if not np.allclose(frame.CalcPoseInBodyFrame(context).GetAsMatrix4(), np.eye(4), atol=1e-12):
            return None
    return j


def _disc(inspector, geometries):
    """(geometry, radius, (x, y) of the disc's centre in the body, (z0, z1)) of the widest upright cylinder
    inside one of the body's collision shapes, or None."""
    best = None
    for g in geometries:
        shape, X = inspector.GetShape(g), inspector.GetPoseInFrame(g).GetAsMatrix4()
        half = _upright(shape, X[:3, :3])
        if half is None:
            continue
        r, hz = half
        if r > 0 and hz > BAND_MARGIN and (best is None or r > best[1]):
            best = (g, r, (float(X[0, 3]), float(X[1, 3])), (float(X[2, 3] - hz), float(X[2, 3] + hz)))
    return best


def _upright(shape, R: np.ndarray):
    """(inscribed disc radius, half height) of an upright box, cylinder or capsule (its straight part), or None."""
    if isinstance(shape, Box):
        k = _vertical_axis(R)
        if k is None:
            return None
        half = np.asarray(shape.size(), float) / 2
        return float(min(half[i] for i in range(3) if i != k)), float(half[k])
    if isinstance(shape, (Cylinder, Capsule)) and _vertical_axis(R) == 2:
        return float(shape.radius()), float(shape.length() / 2)
    return None


def _vertical_axis(R: np.ndarray) -> int | None:
    """The column of R within TILT of vertical, or None."""
    k = int(np.argmax(np.abs(R[2])))
    return k if math.sqrt(max(0.0, 1.0 - R[2, k] ** 2)) <= TILT else None


def footprint(shape, X_WG: np.ndarray, z0: float, z1: float):
    """The 2D solid inside the shape's points between heights z0 and z1, as seen from above.

    Returns:
        a :class:`Solid`; None when the shape lies wholly above or below; False when it cannot be
        represented soundly here (left out).
    """
    R, p = X_WG[:3, :3], X_WG[:3, 3]
    if isinstance(shape, (Sphere, Capsule)):  # a sphere: a capsule of length 0
        h = shape.length() / 2 if isinstance(shape, Capsule) else 0.0
        if h and _vertical_axis(R) != 2:
            return False
        d = max(z0 - (p[2] + h), (p[2] - h) - z1, 0.0)  # from the band to the nearest point of its axis
        r = shape.radius()
        return Solid((p[0], p[1]), (0.0, 0.0), math.sqrt(r * r - d * d)) if d < r else None
    if isinstance(shape, Cylinder):
        if _vertical_axis(R) != 2:
            return False
        h = shape.length() / 2
        return Solid((p[0], p[1]), (0.0, 0.0), shape.radius()) if p[2] + h > z0 and p[2] - h < z1 else None
    if isinstance(shape, Box):
        k = _vertical_axis(R)
        if k is None:
            return False
        half = np.asarray(shape.size(), float) / 2
        if not (p[2] + half[k] > z0 and p[2] - half[k] < z1):
            return None
        others = [i for i in range(3) if i != k]
        axes = R[:2, others]  # the footprint's axes (orthonormal when the box is upright)
        tilt = math.sqrt(max(0.0, 1.0 - R[2, k] ** 2))
        shrink = 2 * half[k] * tilt + (1e-9 if tilt else 0.0)  # a box tilted by TILT at most: its slices shift this little
        h2 = np.maximum(half[others] - shrink, 0.0)
        return Solid((p[0], p[1]), tuple(h2), 0.0, tuple(map(tuple, axes)))
    return False
