"""Workspace goal regions: bounds on a pose in a reference frame, with free axes (Berenson's TSRs).

A region has a reference frame ``X_WR`` and per-axis bounds on the pose
(x, y, z, roll, pitch, yaw) of a sampled frame S in R; ``X_SE`` takes S to the
constrained frame. A bound with lower == upper fixes that axis. Two kinds:

* ``workspace`` — the pose of the robot's end-effector frame ``frame``;
* ``placement`` — the pose of the *carried object* (pick and place); the IK
  sampler turns it into a pose of the carrying body through the grasp.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.geometry import Pose
from lazyground.regions.base import GoalRegion, RegionDrawing, register_region

MIN_DRAWN_SIZE = 0.03  # m: a point-like region (a top grasp) stays visible


@dataclass(frozen=True)
class PoseRegion(GoalRegion):
    """Bounds on a 6-D pose (x, y, z, roll, pitch, yaw) of a frame in ``X_WR``; sampled by IK."""

    frame: str = ""  # workspace: the end-effector frame
    X_WR: Pose = Pose()  # the region's reference frame in world
    X_SE: Pose = Pose()  # the constrained frame relative to the sampled frame (TSR T_we)
    # the pre-pose the motion comes from, as an offset of the target frame in its own
    # axes (e.g. (-0.08, 0, 0): 8 cm back along a gripper's approach axis)
    approach: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self):
        super().__post_init__()
        if len(self.lower) != 6:
            raise ValueError("workspace bounds are (x, y, z, roll, pitch, yaw)")

    def pose_in_world(self, v: np.ndarray) -> Pose:
        """World pose X_WR · X_RS(v) · X_SE of a 6-vector drawn from the region."""
        return self.X_WR.compose(Pose(tuple(v[:3]), tuple(v[3:6]))).compose(self.X_SE)

    def coordinates_of(self, X_WE: np.ndarray) -> np.ndarray:
        """A world pose ``X_WE`` (4x4) as a 6-vector in the sampled frame S (inverse of :meth:`pose_in_world`).

        X_RS = X_WR^-1 · X_WE · X_SE^-1; callers test :meth:`contains` on the result.
        """
        X_RS = np.linalg.inv(self.X_WR.matrix()) @ X_WE @ np.linalg.inv(self.X_SE.matrix())
        p = Pose.from_matrix(X_RS)
        return np.array(p.xyz + p.rpy)

    def robot_target(self, X_WT: Pose, attached) -> tuple[str, Pose]:
        """The robot frame IK constrains and its world pose, for a target ``X_WT`` of this region.

        Args:
            X_WT: a pose from :meth:`pose_in_world` (possibly moved to its pre-pose).
            attached: the world's carried object (an Attachment with ``body`` and ``X_BO``) or None.

        Raises:
            ValueError: the kind needs an attached object and there is none.
        """
        raise NotImplementedError

    def constrained_pose(self, q: np.ndarray, world) -> Pose:
        """World pose of what the region bounds (end effector, carried object) at planned ``q`` of ``world``.

        Raises:
            ValueError: the kind needs an attached object and the world carries none.
        """
        raise NotImplementedError

    def reached(self, q: np.ndarray, world, tol: float = 1e-6) -> bool:
        """Whether the pose bounded by the region, at ``q`` (forward kinematics in ``world``), is in the bounds within ``tol``."""
        return self.contains(self.coordinates_of(self.constrained_pose(q, world).matrix()), tol)

    def _json_fields(self) -> dict:
        return {"frame": self.frame, "X_WR": self.X_WR.to_json(), "X_SE": self.X_SE.to_json(), "approach": list(self.approach)}

    def drawing(self, scene) -> RegionDrawing:
        """The box of the position bounds in the reference frame."""
        lo, hi = np.asarray(self.lower[:3], float), np.asarray(self.upper[:3], float)
        size = np.maximum(hi - lo, MIN_DRAWN_SIZE)
        return RegionDrawing(self.id, tuple(float(s) for s in size), self.X_WR.compose(Pose(tuple(float(c) for c in (lo + hi) / 2))))


@register_region
@dataclass(frozen=True)
class WorkspaceRegion(PoseRegion):
    """Poses of the end-effector frame ``frame`` (a grasp)."""

    kind = "workspace"

    def robot_target(self, X_WT: Pose, attached) -> tuple[str, Pose]:
        return self.frame, X_WT

    def constrained_pose(self, q: np.ndarray, world) -> Pose:
        return world.frame_pose(self.frame, q)


@register_region
@dataclass(frozen=True)
class PlacementRegion(PoseRegion):
    """Poses of the carried object (a placement); the carrying body follows through the grasp X_BO."""

    kind = "placement"

    def robot_target(self, X_WT: Pose, attached) -> tuple[str, Pose]:
        if attached is None:
            raise ValueError(f"placement region {self.id} needs a world with an attached object")
        return attached.body, X_WT.compose(attached.X_BO.inverse())

    def constrained_pose(self, q: np.ndarray, world) -> Pose:
        attached = getattr(world, "attached", None)
        if attached is None:
            raise ValueError(f"placement region {self.id} needs a world with an attached object")
        return world.frame_pose(attached.body, q).compose(attached.X_BO)
