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


class Coin(RoundRobinGoalSource):
    """Region j is valid with probability rates[j]; fails 'in collision' or 'out of reach' otherwise."""

    reached_reasons = ("in collision",)

    def __init__(self, regions, rates, **kw):
        super().__init__(regions, **kw)
        self.rates, self.order = rates, []

    def attempt(self, j, rng, stop):
        self.order.append(j)
        if rng.random() < self.rates[j]:
            from lazyground.planning.problem import GoalSample

            return GoalSample(q=np.zeros(1), region=j), ""
        return None, "in collision" if rng.random() < 0.2 else "out of reach"


def _reference_order(source_regions, rates, seed, draws, give_up):
    """The round robin as planned before #33 (every region's budget listed on each plan): the attempts' regions."""
    stats = [[0, 0, set()] for _ in source_regions]  # attempts, valid, reasons
    rng, order, position = np.random.default_rng(seed), [], 0
    budget = lambda j: give_up * (REACHED_FACTOR if "in collision" in stats[j][2] else 1)
    exhausted = lambda j: stats[j][1] == 0 and stats[j][0] >= budget(j)
    for n in draws:
        got, left_budget = 0, n * 10
        while got < n and left_budget > 0 and not all(exhausted(j) for j in range(len(stats))):
            m, j = len(stats), None
            for step in range(m):
                if not exhausted((position + step) % m):
                    j = (position + step) % m
                    position += step + 1
                    break
            order.append(j)
            left_budget -= 1
            stats[j][0] += 1
            if rng.random() < rates[j]:
                stats[j][1] += 1
                got += 1
            elif rng.random() < 0.2:
                stats[j][2].add("in collision")
    return order


def test_the_round_robin_order_is_unchanged_by_the_incremental_bookkeeping():
    """Issue #33: draws no longer list every region's budget (O(N) per draw); the order of attempts is the same."""
    rates = [0.0] * 37 + [0.05, 0.0, 0.3]
    regions = tuple(ConfigRegion(id=f"r{k}", interpretation=f"i{k}", object=f"o{k}", lower=(0.0,), upper=(1.0,))
                    for k in range(len(rates)))
    draws = [1, 3, 1, 2, 5, 1, 1, 4] * 6
    for seed in range(3):
        source = Coin(regions, rates, give_up_after=6)
        rng = np.random.default_rng(seed)
        for n in draws:
            source.draw(n, rng, never())
            assert source.exhausted() == all(source.region_exhausted(j) for j in range(len(regions)))
            assert source.total_attempts == sum(st.attempts for st in source.stats)
        assert source.order == _reference_order(regions, rates, seed, draws, 6)


class Hopeless(RoundRobinGoalSource):
    """Region 0 always out of reach; region 1 out of reach 40 % of the time (seeded), else in the hand's way."""

    hopeless_reasons = ("out of reach",)

    def attempt(self, j, rng, stop):
        return None, "out of reach" if j == 0 or rng.random() < 0.4 else "hand in collision"


def test_a_region_nearly_always_out_of_reach_is_given_up_sooner():
    """Issue #33: given up after HOPELESS_AFTER attempts, not give_up_after; a region out of reach 40 % of the
    time keeps its full budget (over 20 seeds)."""
    from lazyground.goals import HOPELESS_AFTER

    for seed in range(20):
        source = Hopeless(_regions(), give_up_after=50)
        rng = np.random.default_rng(seed)
        while not source.exhausted():
            source.draw(10, rng, never())
        assert [st.attempts for st in source.stats] == [HOPELESS_AFTER, 50]


class Counting(RoundRobinGoalSource):
    """Every attempt valid; counts the regions whose budget is read (issue #33: no O(N) scan per draw)."""

    def __init__(self, regions):
        self.budget_reads = 0
        super().__init__(regions, give_up_after=5)
        self.budget_reads = 0  # the open list is built once at construction; only the draws' reads count

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


class Screened(RoundRobinGoalSource):
    """Region 0 fails the screen ('hand in collision') until attempt ``passes_from``, then reaches the solver; regions
    1 and 2 always reach it ('in collision'); never a valid sample."""

    screened_reasons = ("out of reach", "hand in collision")

    def __init__(self, regions, passes_from=10**9, **kw):
        super().__init__(regions, **kw)
        self.passes_from = passes_from

    def attempt(self, j, rng, stop):
        screened = j == 0 and self.stats[0].attempts < self.passes_from
        return None, "hand in collision" if screened else "in collision"


def _three():
    return tuple(ConfigRegion(id=f"r{k}", interpretation=f"i{k}", object=f"o{k}", lower=(0.0,), upper=(1.0,)) for k in range(3))


def _attempts(source, total):
    rng = np.random.default_rng(0)
    while source.total_attempts < total:
        source.draw(1, rng, never())
    return [st.attempts for st in source.stats]


def test_a_region_whose_targets_fail_the_screen_takes_one_turn_in_defer():
    """Issue #33: after DEFER_AFTER attempts none of which reached the solver, region 0 takes one round-robin turn in
    DEFER; it is not given up; without screened reasons (or once its targets pass) it takes every turn."""
    from lazyground.goals import DEFER, DEFER_AFTER

    deferred = _attempts(Screened(_three(), give_up_after=10**6), 3 * DEFER_AFTER + 2 * DEFER * 40)
    assert abs(deferred[0] - (DEFER_AFTER + 40)) <= 4 and abs(deferred[1] - deferred[2]) <= 1
    plain = Screened(_three(), give_up_after=10**6)
    plain.screened_reasons = ()
    assert max(_attempts(plain, 600)) - min(_attempts(plain, 600)) <= 1
    back = _attempts(Screened(_three(), passes_from=DEFER_AFTER + 10, give_up_after=10**6), 3000)
    assert back[0] > 900  # one target past the screen brings its share back: every turn again
