"""Goal regions: what a grounding hands to the goal sampler.

Two kinds, one dataclass:

* ``config`` — a box in the planned coordinates (e.g. a car's x, y, heading).
  Coordinates listed in ``wrap`` are angles; their bounds may cross pi.
* ``workspace`` — a Berenson-style workspace goal region for an end-effector
  frame: a reference frame ``X_WR`` plus per-axis bounds on the pose
  (x, y, z, roll, pitch, yaw) of the end-effector frame in R. A bound with
  lower == upper fixes that axis.
* ``placement`` — like ``workspace`` but the bounds are on the pose of the
  *carried object* (pick and place); the sampler composes it with the grasp.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lazyground.geometry import Pose, wrap_angle

KINDS = ("config", "workspace", "placement")


@dataclass(frozen=True)
class GoalRegion:
    """One goal region GR_j of one interpretation I_i (paper Definition 2)."""

    id: str
    interpretation: str
    object: str
    kind: str
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    frame: str = ""  # workspace: the end-effector frame; placement: the carried object id
    X_WR: Pose = Pose()  # workspace/placement: the region's reference frame in world
    X_SE: Pose = Pose()  # workspace: end-effector frame relative to the sampled frame (TSR T_we)
    wrap: tuple[int, ...] = ()  # config: indices of angle coordinates
    # workspace/placement: the pre-pose the motion comes from, as an offset of the target
    # frame in its own axes (e.g. (-0.08, 0, 0): 8 cm back along a gripper's approach axis)
    approach: tuple[float, float, float] = (0.0, 0.0, 0.0)
    label: str = ""  # e.g. "top grasp", "face +x", "forwards"
    attributes: dict = field(default_factory=dict, compare=False)

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"unknown goal region kind {self.kind!r}")
        if len(self.lower) != len(self.upper):
            raise ValueError("lower and upper bounds differ in length")
        if self.kind != "config" and len(self.lower) != 6:
            raise ValueError("workspace bounds are (x, y, z, roll, pitch, yaw)")
        for i, (lo, hi) in enumerate(zip(self.lower, self.upper)):
            if lo > hi and i not in self.wrap:
                raise ValueError(f"region {self.id}: lower > upper on axis {i}")

    def sample(self, rng: np.random.Generator) -> np.ndarray:
        """A uniform draw in the bounds (angles wrap where listed)."""
        lo, hi = np.asarray(self.lower, float), np.asarray(self.upper, float)
        span = hi - lo
        for i in self.wrap:
            if span[i] < 0:  # a wrapped interval such as [3.0, -3.0]
                span[i] += 2 * np.pi
        v = lo + rng.random(len(lo)) * span
        if self.wrap:
            idx = list(self.wrap)
            v[idx] = wrap_angle(v[idx])
        return v

    def contains(self, v: np.ndarray, tol: float = 1e-6) -> bool:
        """Whether a config (kind ``config``) or a 6-vector in R lies in the bounds."""
        v = np.asarray(v, float)
        for i, (x, lo, hi) in enumerate(zip(v, self.lower, self.upper)):
            if i in self.wrap:
                mid = lo + wrap_angle(hi - lo) / 2 if hi >= lo else lo + (hi - lo + 2 * np.pi) / 2
                half = (hi - lo) / 2 if hi >= lo else (hi - lo + 2 * np.pi) / 2
                if abs(wrap_angle(x - mid)) > half + tol:
                    return False
            elif not lo - tol <= x <= hi + tol:
                return False
        return True

    def pose_in_world(self, v: np.ndarray) -> Pose:
        """World pose X_WR · X_RS(v) · X_SE of a 6-vector drawn from a workspace/placement region."""
        return self.X_WR.compose(Pose(tuple(v[:3]), tuple(v[3:6]))).compose(self.X_SE)

    def to_json(self) -> dict:
        out = {
            "id": self.id,
            "kind": self.kind,
            "label": self.label,
            "object": self.object,
            "lower": [round(x, 6) for x in self.lower],
            "upper": [round(x, 6) for x in self.upper],
        }
        if self.kind != "config":
            out["frame"] = self.frame
            out["X_WR"] = self.X_WR.to_json()
            out["X_SE"] = self.X_SE.to_json()
            out["approach"] = list(self.approach)
        return out
