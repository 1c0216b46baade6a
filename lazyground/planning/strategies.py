"""Goal-selection strategies for the goal-biased extensions of Algorithm 1.

Registered by name in :data:`STRATEGIES`. A strategy holds indices into the
planner's list of goal samples; the planner tells it the outcome of each
goal-biased extension and asks whether more samples are wanted.
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass
from typing import Callable, Protocol

import numpy as np

from lazyground.settings import Strategy, coerce


@dataclass(frozen=True)
class StrategySettings:
    resample_threshold: float = 0.2  # reward-penalty: a weight below this asks for more samples
    resample_weight: float = 0.5  # reward-penalty: existing weights are reset to this on resampling


class GoalSelector(Protocol):
    def add(self, indices: list[int]) -> None: ...
    def select(self, rng: np.random.Generator) -> int: ...
    def reward(self, index: int) -> None: ...
    def penalize(self, index: int) -> bool:
        """Record a failed extension; True asks the planner for more goal samples."""
        ...
    def weight(self, index: int) -> float: ...


def reward_weight(w: float) -> float:
    """w / (1 - w) if w < 1, capped at 1 (paper Sec. III-B)."""
    return 1.0 if w >= 0.5 else w / (1.0 - w)


def penalty_weight(w: float) -> float:
    """w / (w + 1) (paper Sec. III-B)."""
    return w / (w + 1.0)


class RewardPenalty:
    """Max-heap of goal-sample weights (Hernández, Moll, Kavraki 2019, Alg. 1 and Sec. III-C).

    New samples enter at weight 1.0. Ties go to the sample added first. When a
    penalty takes a weight below ``resample_threshold``, :meth:`penalize`
    returns True; the planner then draws more samples and calls :meth:`add`,
    which resets every existing weight to ``resample_weight`` (0.5) so that all
    old samples are tried again before the next resampling.
    """

    def __init__(self, settings: StrategySettings = StrategySettings()):
        self._settings = settings
        self._w: dict[int, float] = {}
        self._heap: list[tuple[float, int]] = []  # (-weight, index); index breaks ties

    def add(self, indices: list[int]) -> None:
        if self._w:
            for i in self._w:
                self._w[i] = self._settings.resample_weight
        for i in indices:
            self._w[i] = 1.0
        self._heap = [(-w, i) for i, w in self._w.items()]
        heapq.heapify(self._heap)

    def select(self, rng: np.random.Generator) -> int:
        return self._heap[0][1]

    def weight(self, index: int) -> float:
        return self._w[index]

    def _update(self, index: int, w: float) -> None:
        self._w[index] = w
        # The updated sample is nearly always the top; rebuild otherwise (rare).
        if self._heap and self._heap[0][1] == index:
            heapq.heapreplace(self._heap, (-w, index))
        else:
            self._heap = [(-v, i) for i, v in self._w.items()]
            heapq.heapify(self._heap)

    def reward(self, index: int) -> None:
        w = self._w[index]
        if w < 1.0:
            self._update(index, reward_weight(w))

    def penalize(self, index: int) -> bool:
        w = penalty_weight(self._w[index])
        self._update(index, w)
        return w < self._settings.resample_threshold


class Consecutive:
    """Round-robin over the goal samples in the order drawn, as OMPL's ``GoalStates``."""

    def __init__(self, settings: StrategySettings = StrategySettings()):
        self._order: list[int] = []
        self._next = 0

    def add(self, indices: list[int]) -> None:
        self._order.extend(indices)

    def select(self, rng: np.random.Generator) -> int:
        i = self._order[self._next % len(self._order)]
        self._next = (self._next + 1) % len(self._order)  # as OMPL GoalStates::sampleGoal
        return i

    def weight(self, index: int) -> float:
        return 1.0

    def reward(self, index: int) -> None:
        pass

    def penalize(self, index: int) -> bool:
        return False


class Random(Consecutive):
    """A uniformly random goal sample for each goal-biased extension."""

    def select(self, rng: np.random.Generator) -> int:
        return self._order[int(rng.integers(len(self._order)))]


def _cover(settings: StrategySettings) -> GoalSelector:
    from lazyground.planning.cover import Cover  # (its module imports this one)

    return Cover(settings)


STRATEGIES: dict[Strategy, Callable[[StrategySettings], GoalSelector]] = {
    Strategy.REWARD_PENALTY: RewardPenalty,
    Strategy.CONSECUTIVE: Consecutive,
    Strategy.RANDOM: Random,
    Strategy.COVER: _cover,
}


def make_strategy(name: str, settings: StrategySettings = StrategySettings()) -> GoalSelector:
    """The goal selector registered for ``name``.

    Raises:
        ValueError: ``name`` is not a known strategy (the message lists them).
    """
    return STRATEGIES[coerce("strategy", name)](settings)
