"""What every goal-selection strategy shares: its settings, its protocol and the paper's weight updates.

A module of its own so that strategies in other modules (:mod:`lazyground.planning.cover`) and the
registry in :mod:`lazyground.planning.strategies` both import it, with no cycle between them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np


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
