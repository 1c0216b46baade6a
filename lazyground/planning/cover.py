"""Reward-penalty that covers the goal regions as the search rejects them (issue #33).

With many interpretations and few reachable, the paper's rule draws more goal samples only
when the *selected* sample is stuck, then resets every weight to 0.5 and rebuilds the heap
(O(N) per resampling); the two-tree planner waits until *every* sample is stuck (a scan over
all of them per penalty). Both leave most regions without a sample for a long time: the goal
source hands samples out region by region, so the reachable region's turn comes after about
N / resample_count resamplings.

:class:`Cover` keeps the reward-penalty weights but (1) asks for one new sample whenever a
sample it penalises falls below the threshold, whatever the others' weights (a region whose
goal tree stays blocked makes room for the next region at once), and (2) never resets the old
weights: a new sample enters at weight 1 on a lazily updated max-heap, so select, reward and
penalty cost O(log N), not O(N).
"""

from __future__ import annotations

import heapq

import numpy as np

from lazyground.planning.strategies import StrategySettings, penalty_weight, reward_weight


class Cover:
    """Reward-penalty weights on a lazy max-heap; a stuck sample asks for one more sample at once."""

    resample_alone = True  # a stuck sample asks for samples even while other samples progress
    batch = 1  # samples drawn per request

    def __init__(self, settings: StrategySettings = StrategySettings()):
        self._threshold = settings.resample_threshold
        self._w: dict[int, float] = {}
        self._heap: list[tuple[float, int]] = []  # (-weight, index); stale entries skipped

    def add(self, indices: list[int]) -> None:
        for i in indices:
            self._w[i] = 1.0
            heapq.heappush(self._heap, (-1.0, i))

    def select(self, rng: np.random.Generator) -> int:
        while -self._heap[0][0] != self._w[self._heap[0][1]]:
            heapq.heappop(self._heap)
        return self._heap[0][1]

    def weight(self, index: int) -> float:
        return self._w[index]

    def _set(self, index: int, w: float) -> None:
        if w != self._w[index]:
            self._w[index] = w
            heapq.heappush(self._heap, (-w, index))

    def reward(self, index: int) -> None:
        self._set(index, reward_weight(self._w[index]) if self._w[index] < 1.0 else 1.0)

    def penalize(self, index: int) -> bool:
        w = penalty_weight(self._w[index])
        self._set(index, w)
        return w < self._threshold
