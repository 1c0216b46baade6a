"""Goal sources: lazily turn goal regions into valid goal configurations.

:class:`RoundRobinGoalSource` owns the bookkeeping shared by every sampler
(round-robin over regions, per-region statistics, giving up on a region that
never yields a valid sample); subclasses say how one attempt on one region
goes. :class:`ConfigGoalSource` covers C-space regions (parking); the Drake IK
sampler for workspace regions lives in :mod:`lazyground.drake.ik`.
"""

from __future__ import annotations

import time

import numpy as np

from lazyground.planning.problem import GoalSample, RegionStats, ValidityChecker
from lazyground.planning.space import ConfigSpace
from lazyground.regions import GoalRegion


class RoundRobinGoalSource:
    """Draw goal samples region by region, so every grounding gets a chance.

    A region that has had ``give_up_after`` attempts without one valid sample
    is exhausted and skipped from then on.
    """

    def __init__(self, regions: tuple[GoalRegion, ...], give_up_after: int = 50, attempts_per_sample: int = 10):
        self.regions = tuple(regions)
        self.stats = [RegionStats() for _ in self.regions]
        self._give_up_after = give_up_after
        self._attempts_per_sample = attempts_per_sample
        self._next = 0
        self._time = 0.0

    @property
    def sample_time(self) -> float:
        return self._time

    def region_exhausted(self, j: int) -> bool:
        st = self.stats[j]
        return st.valid == 0 and st.attempts >= self._give_up_after

    def exhausted(self) -> bool:
        return all(self.region_exhausted(j) for j in range(len(self.regions)))

    def draw(self, n: int, rng: np.random.Generator, deadline: float) -> list[GoalSample]:
        out: list[GoalSample] = []
        budget = n * self._attempts_per_sample
        t0 = time.perf_counter()
        try:
            while len(out) < n and budget > 0 and not self.exhausted() and time.perf_counter() < deadline:
                j = self._next % len(self.regions)
                self._next += 1
                if self.region_exhausted(j):
                    continue
                budget -= 1
                st = self.stats[j]
                st.attempts += 1
                a0 = time.perf_counter()
                sample, reason = self.attempt(j, rng, deadline)
                st.time += time.perf_counter() - a0
                if sample is None:
                    st.fail(reason)
                else:
                    st.valid += 1
                    out.append(sample)
        finally:
            self._time += time.perf_counter() - t0
        return out

    def attempt(self, j: int, rng: np.random.Generator, deadline: float) -> tuple[GoalSample | None, str]:
        """One try at a valid sample in region j: (sample, "") or (None, reason)."""
        raise NotImplementedError


class ConfigGoalSource(RoundRobinGoalSource):
    """Uniform samples from C-space box regions, kept when collision-free."""

    def __init__(self, regions, space: ConfigSpace, checker: ValidityChecker, **kwargs):
        super().__init__(regions, **kwargs)
        for r in self.regions:
            if r.kind != "config" or len(r.lower) != space.dim:
                raise ValueError(f"region {r.id} is not a {space.dim}-D configuration region")
        self._space = space
        self._checker = checker

    def attempt(self, j, rng, deadline):
        q = self.regions[j].sample(rng)
        if not self._space.within_bounds(q):
            return None, "outside limits"
        if not self._checker.config_free(q):
            return None, "in collision"
        return GoalSample(q=q, region=j), ""
