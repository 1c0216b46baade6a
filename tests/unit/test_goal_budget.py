"""Issue 34: goal sampling keeps trying a region whose goals are reached but collide (another goal of it may be
free) and gives up as before on one it never reaches; the status says how many of what were tried per region."""

import numpy as np

from lazyground.goals import REACHED_FACTOR, RoundRobinGoalSource
from lazyground.planning.stop import never
from lazyground.regions import ConfigRegion


class Scripted(RoundRobinGoalSource):
    """Region 0: every attempt reached but collides; region 1: never reached; never a valid sample."""

    reached_reasons = ("in collision",)

    def attempt(self, j, rng, stop):
        return None, ("in collision", "out of reach")[j]


def _regions():
    return tuple(ConfigRegion(id=f"r{k}", interpretation=f"i{k}", object=f"o{k}", lower=(0.0,), upper=(1.0,)) for k in range(2))


def test_a_region_whose_goals_are_reached_gets_more_attempts():
    source = Scripted(_regions(), give_up_after=20)
    rng = np.random.default_rng(0)
    while not source.exhausted():
        assert source.draw(10, rng, never()) == []
    assert [st.attempts for st in source.stats] == [20 * REACHED_FACTOR, 20]


def test_without_reached_reasons_every_region_gets_the_same_budget():
    source = Scripted(_regions(), give_up_after=20)
    source.reached_reasons = ()
    rng = np.random.default_rng(0)
    while not source.exhausted():
        source.draw(10, rng, never())
    assert [st.attempts for st in source.stats] == [20, 20]


class Counting(RoundRobinGoalSource):
    """Every attempt valid; counts the regions whose budget is read (issue #33: no O(N) scan per draw)."""

    def __init__(self, regions):
        super().__init__(regions, give_up_after=5)
        self.budget_reads = 0

    def region_budget(self, j):
        self.budget_reads += 1
        return super().region_budget(j)

    def attempt(self, j, rng, stop):
        from lazyground.planning.problem import GoalSample

        return GoalSample(q=np.zeros(1), region=j), ""


def test_one_sample_costs_the_same_whatever_the_number_of_regions():
    reads = []
    for n in (8, 512):
        regions = tuple(ConfigRegion(id=f"r{k}", interpretation=f"i{k}", object=f"o{k}", lower=(0.0,), upper=(1.0,))
                        for k in range(n))
        source, rng = Counting(regions), np.random.default_rng(0)
        for _ in range(20):
            assert len(source.draw(1, rng, never())) == 1
        reads.append(source.budget_reads)
        attempts = [st.attempts for st in source.stats]
        assert sum(attempts) == 20 and max(attempts) - min(attempts) <= 1  # still round-robin
    assert max(reads) <= 3 * 20  # O(draws), not O(regions) (the scan over all of them: 10,051 at 512)
