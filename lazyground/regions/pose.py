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

from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from lazyground.geometry import Pose, rpy_to_matrix, wrap_angle
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
        """Whether the pose bounded by the region, at ``q`` (forward kinematics in ``world``), lies within ``tol``
        metres and ``tol`` radians of a pose of the region (:meth:`pose_error`)."""
        return max(self.pose_error(self.constrained_pose(q, world).matrix())) <= tol

    def pose_error(self, X_WE: np.ndarray) -> tuple[float, float]:
        """(metres, radians) from a world pose ``X_WE`` (4x4) to the nearest pose of the region found.

        Measured on the poses, not on the bounds' coordinates: roll-pitch-yaw is not a metric, so a rotation
        of e about the sampled frame's z, at pitch p, moves roll by e tan p and yaw by e / cos p (an angled
        grasp tilted 42 degrees and met by IK within 0.010 rad lay 0.0128 outside its roll bound). The nearest
        pose: a bounded least-squares fit of (position, rotation vector) residuals over the region's free
        axes, from the pose's coordinates clipped to the bounds.
        """
        lo, span, wrapped = self.unit_map()
        mid = lo + span / 2
        circle = wrapped & (span >= 2 * np.pi - 1e-12)
        low = np.where(circle, -np.inf, mid - span / 2)
        high = np.where(circle, np.inf, mid + span / 2)
        v = self.coordinates_of(X_WE)
        v = np.clip(np.where(wrapped, mid + wrap_angle(v - mid), v), low, high)  # angles on the arc's side of its middle
        free = span > 0
        X_WR, X_SE = self.X_WR.matrix(), self.X_SE.matrix()
        R_EW = X_WE[:3, :3].T

        def residual(x: np.ndarray) -> np.ndarray:
            w = v.copy()
            w[free] = x
            X_RS = np.eye(4)
            X_RS[:3, :3], X_RS[:3, 3] = rpy_to_matrix(w[3:6]), w[:3]
            X = X_WR @ X_RS @ X_SE
            return np.concatenate([X[:3, 3] - X_WE[:3, 3], Rotation.from_matrix(R_EW @ X[:3, :3]).as_rotvec()])

        if free.any():
            v[free] = least_squares(residual, v[free], bounds=(low[free], high[free]), xtol=1e-12, ftol=1e-12, gtol=1e-12).x
        r = residual(v[free])
        return float(np.linalg.norm(r[:3])), float(np.linalg.norm(r[3:]))

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
