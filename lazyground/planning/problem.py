"""The planner's seam: settings, the problem's protocols, and the result.

The planner sees only these: a :class:`ConfigSpace`, a :class:`ValidityChecker`
and a :class:`GoalSource` — never Drake.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition
from lazyground.regions import GoalRegion
from lazyground.settings import PlannerSettings  # noqa: F401  (declared once in lazyground.settings)


class PlanStatus(str, enum.Enum):
    SOLVED = "solved"
    TIMEOUT = "timeout"
    INVALID_START = "invalid_start"
    NO_VALID_GOAL = "no_valid_goal"
    INTERRUPTED = "interrupted"

    def __str__(self) -> str:
        return self.value


class ValidityChecker(Protocol):
    """Collision checks over configurations; times itself.

    A checker may also offer ``config_unpadded_free(q) -> bool``: a cheaper test that
    config_free implies (no penetration, the padding not checked), which the two-tree
    planner uses for its tentative start-tree checks (lazyground.planning.birrt).
    """

    def config_free(self, q: np.ndarray) -> bool: ...
    def configs_free(self, qs: np.ndarray) -> np.ndarray: ...
    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the motion a → b is free, checked no coarser than ``resolution``."""
        ...
    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The largest t in [0, 1] such that a → a + t (b - a) is free at ``resolution``."""
        ...
    def explain(self, q: np.ndarray) -> str:
        """Why q is invalid, one line (e.g. the colliding pair)."""
        ...
    @property
    def check_time(self) -> float: ...
    @property
    def checks(self) -> int:
        """Config and edge checks made so far (an edge check counts once)."""
        ...


@dataclass
class GoalSample:
    """A valid configuration in one goal region, with its reward-penalty record."""

    q: np.ndarray
    region: int  # index into GoalSource.regions
    attempts: int = 0
    rewards: int = 0
    penalties: int = 0
    weight: float = 1.0
    extra: dict = field(default_factory=dict)  # e.g. the end-effector pose it was solved for
    final: np.ndarray | None = None  # where the path ends after the approach from q (None: at q)

    @property
    def end(self) -> np.ndarray:
        """The configuration a path to this sample ends at."""
        return self.q if self.final is None else self.final


@dataclass
class RegionStats:
    attempts: int = 0
    valid: int = 0
    time: float = 0.0
    failures: dict[str, int] = field(default_factory=dict)  # reason -> count
    unreachable: str = ""  # why the region is proven unreachable before any attempt (e.g. "reach prior")

    def fail(self, reason: str) -> None:
        self.failures[reason] = self.failures.get(reason, 0) + 1

    def to_json(self) -> dict:
        out = {"attempts": self.attempts, "valid": self.valid, "time_s": round(self.time, 6), "failures": dict(self.failures)}
        return out | ({"unreachable": self.unreachable} if self.unreachable else {})


def proven_unreachable(regions, stats: list[RegionStats]) -> tuple[int, int, str]:
    """(interpretations all of whose regions are proven unreachable, interpretations, by what: the first reason)."""
    by: dict[str, bool] = {}
    why = ""
    for r, st in zip(regions, stats):
        by[r.interpretation] = by.get(r.interpretation, True) and bool(st.unreachable)
        why = why or st.unreachable
    return sum(by.values()), len(by), why


def unreachable_note(regions, stats: list[RegionStats]) -> str:
    """"k of N interpretations proven unreachable by the reach prior", or "" when none is."""
    k, n, why = proven_unreachable(regions, stats)
    return f"{k} of {n} interpretations proven unreachable by the {why}" if why else ""


class GoalSource(Protocol):
    """Draws valid goal configurations from goal regions, lazily (goalRegionsSampler)."""

    regions: tuple[GoalRegion, ...]
    stats: list[RegionStats]

    def draw(self, n: int, rng: np.random.Generator, stop: StopCondition) -> list[GoalSample]:
        """Up to n new valid samples spread over the regions; fewer if attempts run out or ``stop`` says so."""
        ...
    def exhausted(self) -> bool:
        """True when no region can yield a valid sample any more."""
        ...
    @property
    def sample_time(self) -> float: ...


@dataclass(frozen=True)
class PlanResult:
    """What one planning query returns; records its seed and a time split."""

    status: PlanStatus
    seed: int | None
    path: np.ndarray | None  # (n, dim) configurations, start first
    goal: GoalSample | None
    goal_region: GoalRegion | None
    iterations: int
    tree_size: int
    goal_samples: list[GoalSample]
    resamplings: int
    time_s: float
    goal_sampling_s: float
    collision_s: float
    message: str = ""
    regions: tuple[GoalRegion, ...] = ()  # the goal source's regions; GoalSample.region indexes these
    region_stats: list[RegionStats] = field(default_factory=list)
    tree: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None  # (nodes, parents, goal-biased flag)
    failed_from: np.ndarray | None = None  # nodes from which a goal-biased extension failed
    path_length: float = 0.0
    invalid_paths_rejected: int = 0
    collision_checks: int = 0  # the planner's config and edge checks (an edge check counts once), not the goal sampler's

    @property
    def solved(self) -> bool:
        return self.status is PlanStatus.SOLVED

    @property
    def other_s(self) -> float:
        return max(0.0, self.time_s - self.goal_sampling_s - self.collision_s)
