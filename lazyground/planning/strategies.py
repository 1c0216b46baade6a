"""Goal-selection strategies for the goal-biased extensions of Algorithm 1.

Registered by name in :data:`STRATEGIES`. A strategy holds indices into the
planner's list of goal samples; the planner tells it the outcome of each
goal-biased extension and asks whether more samples are wanted.
"""

from __future__ import annotations

import heapq
from typing import Callable

import numpy as np

from lazyground.planning.cover import Cover, CoverConnect
from lazyground.planning.weights import GoalSelector, StrategySettings, penalty_weight, reward_weight
from lazyground.settings import Strategy, coerce

__all__ = ["STRATEGIES", "GoalSelector", "StrategySettings", "make_strategy", "penalty_weight", "reward_weight"]


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


STRATEGIES: dict[Strategy, Callable[[StrategySettings], GoalSelector]] = {
    Strategy.REWARD_PENALTY: RewardPenalty,
    Strategy.CONSECUTIVE: Consecutive,
    Strategy.RANDOM: Random,
    Strategy.COVER: Cover,
    Strategy.COVER_CONNECT: CoverConnect,
}


def make_strategy(name: str, settings: StrategySettings = StrategySettings()) -> GoalSelector:
    """The goal selector registered for ``name``.

    Raises:
        ValueError: ``name`` is not a known strategy (the message lists them).
    """
    factory = STRATEGIES.get(name) if isinstance(name, Strategy) else None  # (a member: no check, ~10 µs a search, #31)
    return (factory or STRATEGIES[coerce("strategy", name)])(settings)
