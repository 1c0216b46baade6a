"""A cheap reachability filter for IK targets: where the robot's wrist point can be.

Built once per robot and end-effector frame from random configurations (the
numpy chain in one batch), cached; :class:`lazyground.drake.ik.IKGoalSource`
rejects a target whose wrist point lies far from every sampled one before any
solve.
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
from pydrake.multibody.tree import RevoluteJoint
from scipy.spatial import cKDTree

from lazyground.drake.chain import chain_to_frame, joints_to_world

REACH_SAMPLES = 10000
REACH_SEED = 20190520  # the map is a deterministic property of the robot, not of a plan's rng
START_STRIDE = 4  # IK starts come from every 4th sampled configuration (near_configs)
REACH_CACHE_SIZE = 8  # reach maps kept at once (robots x end-effector frames); ~0.3 MB each
_REACH_MAPS: "OrderedDict[tuple, ReachMap]" = OrderedDict()  # reach_key -> map, least recently used first


@dataclass(frozen=True)
class ReachMap:
    """Where the robot's wrist point can be: world positions over random joint configurations.

    The wrist point W is fixed in the end-effector frame and independent of the
    last joint (or the last two, when they intersect as on Fetch), so a target
    pose fixes where W must be. A target whose W is farther than a margin from
    every sampled W is out of reach; IK on it would fail slowly.
    """

    frame: str
    p_EW: np.ndarray  # wrist point in the end-effector frame
    tree: cKDTree
    configs: np.ndarray  # (REACH_SAMPLES, planned) the sampled configurations, in the tree's order
    start_tree: cKDTree  # the wrist points of every START_STRIDE-th configuration

    def wrist(self, X_WT: np.ndarray) -> np.ndarray:
        return X_WT[:3, :3] @ self.p_EW + X_WT[:3, 3]

    def plausible(self, X_WT: np.ndarray, margin: float) -> bool:
        distance, _ = self.tree.query(self.wrist(X_WT))
        return bool(distance <= margin)

    def plausible_all(self, X_WT: np.ndarray, margin: float) -> np.ndarray:
        """:meth:`plausible` for poses (B, 4, 4) at once, one tree query."""
        distance, _ = self.tree.query(self.wrist_all(X_WT))
        return np.asarray(distance <= margin, bool).reshape(len(X_WT))


    def near_configs(self, X_WT: np.ndarray, count: int, nearest: int, rng: np.random.Generator) -> np.ndarray:
        """For each pose (B, 4, 4): ``count`` distinct random picks among the sampled configurations whose wrist
        points lie closest to the pose's, as (B, count, planned) (IK starts near the pose).

        The picks are among the ``nearest`` / START_STRIDE nearest of every START_STRIDE-th configuration: about
        the neighbourhood of the ``nearest`` nearest of all, for a quarter of the query's cost (scipy's k-nearest
        query costs ~40 us a pose at k = 256 against ~10 us at 64).
        """
        k = max(nearest // START_STRIDE, count)
        _, index = self.start_tree.query(self.wrist_all(X_WT), k=k)
        index = np.asarray(index).reshape(len(X_WT), k)
        pick = np.argsort(rng.random(index.shape), axis=1)[:, :count]
        return self.configs[START_STRIDE * np.take_along_axis(index, pick, axis=1)]

    def wrist_all(self, X_WT: np.ndarray) -> np.ndarray:
        """The wrist points (B, 3) of poses (B, 4, 4)."""
        return X_WT[:, :3, :3] @ self.p_EW + X_WT[:, :3, 3]


def reach_key(world, frame: str) -> tuple:
    """What a reach map depends on: the model, its base weld, the planned coordinates
    (names, limits, wrapping), the held positions and the frame."""
    robot, space = world.scene.robot, world.space
    base = robot.base.pose() if robot.base is not None else None
    return (robot.model, robot.base_link, base, space.names, tuple(space.lower), tuple(space.upper), tuple(space.wrap),
            tuple(world.q_full), frame)


def reach_map(world, frame: str) -> ReachMap:
    """The reach map of ``frame`` in ``world``, cached by :func:`reach_key` (at most REACH_CACHE_SIZE kept)."""
    key = reach_key(world, frame)
    if key in _REACH_MAPS:
        _REACH_MAPS.move_to_end(key)
        return _REACH_MAPS[key]
    _REACH_MAPS[key] = m = _build_reach_map(world, frame)
    while len(_REACH_MAPS) > REACH_CACHE_SIZE:
        _REACH_MAPS.popitem(last=False)
    return m


def _build_reach_map(world, frame: str) -> ReachMap:
    kin = world.kinematics
    E = kin.frame(frame)
    X_WE = kin.X_WF(E, world.q_full)
    joints = _joints_to_root(kin.plant, E.body())
    # W: the child-side origin of the last movable joint; one joint further up while
    # that joint's origin lies on the axis of the joint below it (a spherical-ish wrist).
    W = joints[0].frame_on_child() if joints else E
    for below, above in zip(joints, joints[1:]):
        if not isinstance(below, RevoluteJoint):
            break
        X_Wb = kin.X_WF(below.frame_on_child(), world.q_full)
        axis = X_Wb.rotation() @ below.revolute_axis()
        o = kin.X_WF(above.frame_on_child(), world.q_full).translation()
        r = o - X_Wb.translation()
        if np.linalg.norm(r - axis * (r @ axis)) > 1e-6:
            break
        W = above.frame_on_child()
    p_EW = X_WE.inverse() @ kin.X_WF(W, world.q_full).translation()
    rng = np.random.default_rng(REACH_SEED)
    qs = np.tile(world.q_full, (REACH_SAMPLES, 1))
    space = world.space  # as REACH_SAMPLES calls of space.sample(rng): the same draws, in one call
    qs[:, world.planned] = space.lower + rng.random((REACH_SAMPLES, space.dim)) * (space.upper - space.lower)
    try:  # all samples in one batch (~50x faster than asking the plant one by one)
        chain = chain_to_frame(kin.plant, W)
        points = chain.forward(qs[:, chain.index])[:, :3, 3]
    except ValueError:  # a joint the chain cannot express (e.g. a planar base): ask the plant
        points = np.array([kin.X_WF(W, q).translation() for q in qs])
    return ReachMap(frame, np.asarray(p_EW), cKDTree(points), qs[:, world.planned], cKDTree(points[::START_STRIDE]))


def _joints_to_root(plant, body) -> list:
    """Movable joints from ``body`` up to the world, nearest first."""
    return [j for j in joints_to_world(plant, body) if j.num_positions() > 0]
