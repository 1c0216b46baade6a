"""What a task returns: typed steps, each with its PlanResult, and what was carried.

No untyped dictionaries: a consumer (JSON output, viewers, validators) reads the
fields below, in process, as numpy arrays and :class:`~lazyground.geometry.Pose`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.geometry import Pose
from lazyground.planning.problem import PlanResult


@dataclass(frozen=True)
class Grasp:
    """How an object is held: the gripper frame's pose when it was reached, and the object in it."""

    object_id: str
    region: str  # the grasp region's id
    label: str  # the grasp region's label ("top", "side", ...)
    frame: str  # the gripper frame the object rides on
    X_WG: Pose  # gripper frame in world at the grasp
    X_GO: Pose  # object in gripper frame (fixed while carried)


@dataclass(frozen=True)
class Lift:
    """The lift-off after grasping: waypoints from the grasp to a collision-free pose above it."""

    path: np.ndarray
    height: float

    @property
    def q_lift(self) -> np.ndarray:
        return self.path[-1]


@dataclass(frozen=True)
class Placement:
    """Where a carried object was put down."""

    region: str
    target: str  # the surface's object id
    X_WO: Pose  # the object in world when released


@dataclass(frozen=True)
class ObjectStep:
    """What became of one object of a several-object request (issue #30)."""

    object: str | None  # None: no candidate was left to try
    status: str  # "done", "already there", "not done"; picking up several: "stowed" (put down), "held" (the last)
    target: str | None = None  # where it was put (or already is)
    why: str = ""  # not done: the planner's reason; done: which candidates were passed over
    placement: Placement | None = None  # done / stowed: the region and the pose it was put down at
    step: int | None = None  # done / stowed / held: the index of its pick step in Outcome.steps

    def to_json(self) -> dict:
        out = {"object": self.object, "status": self.status, "target": self.target, "why": self.why, "step": self.step}
        if self.placement is not None:
            out["placement"] = {"region": self.placement.region, "X_WO": self.placement.X_WO.to_json()}
        return out


@dataclass(frozen=True)
class Step:
    """One planned motion of a task."""

    label: str  # e.g. "park", "pick cup_red", "place cup_red"
    result: PlanResult
    setup_s: float = 0.0  # building the world this step planned in
    grasp: Grasp | None = None  # the object carried during this step, and how; None: nothing carried
    motion: object | None = None  # the shortcut and its timing (lazyground.motion.pipeline.Motion; issue #16)
    placement: Placement | None = None  # where the carried object was put down at the end of this step
    lift: Lift | None = None  # the lift-off that leads into this (place) step

    @property
    def trajectory(self):
        """The timed trajectory along ``result.path`` (a lazyground.motion Trajectory), if any."""
        return self.motion.trajectory if self.motion is not None else None

    @property
    def attached(self) -> str | None:
        """The id of the object carried during this step."""
        return self.grasp.object_id if self.grasp else None


@dataclass(frozen=True)
class Outcome:
    """A task's result: its steps in order, the combined result, and pick-and-place data.

    ``result`` is the one PlanResult a caller looks at first: the only step's for one-step
    tasks; for pick and place the steps combined (summed counts, the whole path).
    """

    result: PlanResult
    steps: tuple[Step, ...]
    joint_names: tuple[str, ...]
    notes: tuple[str, ...] = ()
    lift: Lift | None = None
    placement: Placement | None = None
    fallbacks: int = 0  # objects given up on before the one that was placed
    objects: tuple = ()  # several objects (#30): one ObjectStep per object asked for, in order (tasks.several)
    improvements: tuple = ()  # objective shortest/fastest: (time, cost, region) of each better solution (tasks.anytime)
    held: Grasp | None = None  # picking up several (#30): the object in the hand at the end, and how

    @property
    def grasp(self) -> Grasp | None:
        """The grasp of the object held at the end, else of the (last) carried one, if any."""
        if self.held is not None:
            return self.held
        return next((s.grasp for s in reversed(self.steps) if s.grasp is not None), None)

    @property
    def picked(self) -> str | None:
        return self.grasp.object_id if self.grasp else None
