"""PlanReport: one request planned on one scene (what ``api.plan`` returns)."""

from __future__ import annotations

from dataclasses import dataclass

from grounding.model import Grounding, Interpretation
from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.settings import RunSettings
from lazyground.tasks.outcome import Outcome, Step


@dataclass(frozen=True)
class PlanReport:
    """One request planned on one scene: the grounding, the task's outcome and where the time went.

    ``result`` is the outcome's combined result; ``time_s`` counts grounding and planning,
    ``setup_s`` the worlds built for it (zero when the caller passed one), for every task alike.
    """

    request: str
    scene: str
    seed: int
    settings: RunSettings  # the run's: settings.planner, .goal_sampling, .motion, .task
    grounding: Grounding
    result: PlanResult
    joint_names: tuple[str, ...]
    grounding_s: float
    setup_s: float  # building the Drake world(s)
    outcome: Outcome | None = None  # None: a bare result (e.g. a viewer test)
    total_s: float | None = None  # api.plan's wall time less setup_s: the request as the user waits for it

    @property
    def total_split_s(self) -> dict[str, float] | None:
        """``total_s`` split: grounding, search (goal sampling, checks and the rest of the planner), motion
        (shortening and timing every step), and the rest (loading the scene, goal sources, the report); the
        parts add up to ``total_s``."""
        if self.total_s is None:
            return None
        motion = sum(s.motion.shortcut_s + s.motion.timing_s for s in (self.outcome.steps if self.outcome else ())
                     if s.motion is not None)
        split = {"grounding": self.grounding_s, "search": self.result.time_s, "motion": motion}
        split["rest"] = self.total_s - sum(split.values())
        return split

    @property
    def steps(self) -> tuple[Step, ...]:
        """The task's steps when it has more than one (pick and place); empty otherwise."""
        return self.outcome.steps if self.outcome is not None and len(self.outcome.steps) > 1 else ()

    @property
    def notes(self) -> tuple[str, ...]:
        return self.outcome.notes if self.outcome is not None else ()

    @property
    def motion(self):
        """A one-step task's shortcut and timed trajectory (lazyground.motion.pipeline.Motion); None for
        several steps (each Step has its own) or none."""
        if self.outcome is None or len(self.outcome.steps) != 1:
            return None
        return self.outcome.steps[0].motion

    @property
    def cusps(self) -> int | None:
        """A car's gear changes along its path (its motion's; None: not a car, or not solved)."""
        motion = self.motion
        return motion.cusps if motion is not None else None

    @property
    def status(self) -> PlanStatus:
        return self.result.status

    @property
    def time_s(self) -> float:
        """Planning time as a user experiences it: grounding + goal sampling + search."""
        return self.grounding_s + self.result.time_s

    @property
    def chosen(self) -> Interpretation | None:
        region = self.result.goal_region
        if region is None:
            return None
        return next(i for i in self.grounding.interpretations if i.id == region.interpretation)

    @property
    def chosen_object(self) -> str | None:
        """The object acted on: the spot parked in, the object picked (also for pick and place)."""
        picked = self.outcome.picked if self.outcome is not None else None
        if picked is not None:
            return picked
        return self.result.goal_region.object if self.result.goal_region else None

    def step_report(self, step: Step) -> "PlanReport":
        """``step`` as a report of its own (the JSON output's ``steps`` entries)."""
        return PlanReport(step.label, self.scene, self.seed, self.settings, self.grounding, step.result,
                          self.joint_names, 0.0, step.setup_s, Outcome(step.result, (step,), self.joint_names))
