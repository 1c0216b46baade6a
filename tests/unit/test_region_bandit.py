"""Issue #33: cover chooses the regions goal samples come from (planning/region_bandit.py), and pays goal sampling
only for iterations in which no goal tree progresses (Cover.ik_allowance)."""

import numpy as np

from lazyground.goals import RoundRobinGoalSource
from lazyground.planning import PlannerSettings, solve
from lazyground.planning.cover import Cover
from lazyground.planning.problem import GoalSample, RegionStats
from lazyground.planning.region_bandit import BLOCK, DEFER, StagedBandit
from lazyground.planning.stop import StopCondition, never
from lazyground.regions import ConfigRegion
from tests.unit.toy import NO_CLOCK, SPACE, START, WALLS, BoxWorld


def _regions(n):
    return tuple(ConfigRegion(id=f"r{k}", interpretation=f"i{k}", object=f"o{k}", lower=(0.0,), upper=(1.0,)) for k in range(n))


class Rack(RoundRobinGoalSource):
    """Regions below ``near`` are within reach (valid with probability ``rate``, else 'in collision'); the others
    fail 'out of reach' (a rack's cans behind the inner ring)."""

    hopeless_reasons = ("out of reach",)

    def __init__(self, regions, near, rate, **kw):
        super().__init__(regions, **kw)
        self.near, self.rate, self.order = near, rate, []

    def attempt(self, j, rng, stop):
        self.order.append(j)
        if j >= self.near:
            return None, "out of reach"
        return (GoalSample(q=np.zeros(1), region=j), "") if rng.random() < self.rate[j] else (None, "in collision")


def test_regions_within_reach_go_first_and_those_with_a_sample_last():
    b = StagedBandit([RegionStats() for _ in range(6)], ("out of reach",))
    b.observe(0, False, True)  # out of reach
    b.observe(1, False, False)  # within reach, missed
    b.observe(2, True, False)  # valid
    assert b.block(list(range(6)))[:4] == [1, 3, 4, 5]  # within reach before the untried, the untried in order
    assert b.block(list(range(6)))[4:] == [0, 2]  # then the one out of reach; the one with a sample last
    for _ in range(30):  # a region within reach that keeps missing falls behind the once out of reach
        b.observe(1, False, False)
    assert b.block([0, 1]) == [0, 1]


def test_the_bandit_starts_from_the_sources_counts():
    st = [RegionStats(attempts=3, failures={"out of reach": 3}), RegionStats(attempts=3, valid=1, failures={"in collision": 2})]
    b = StagedBandit(st, ("out of reach",))
    assert list(b.passed) == [0, 3] and list(b.valid) == [0, 1]


def test_a_plan_from_a_counter_is_the_same_when_made_again():
    """The batch solver prepares attempts ahead by planning from the draw's counter again: the chooser's schedule
    keeps the counter's region fixed once chosen."""
    source = Rack(_regions(40), near=5, rate=[0.0] * 5)
    source.chooser = StagedBandit(source.stats, source.hopeless_reasons)
    first = source.plan(0, 3 * BLOCK)
    source.draw(2, np.random.default_rng(0), never())  # changes the counts
    assert source.plan(0, 3 * BLOCK) == first
    assert [j for j, _ in source.plan(0, 3)] == [0, 1, 2] and [a for _, a in source.plan(7, 3)] == [8, 9, 10]


def test_the_chooser_spends_fewer_attempts_before_the_reachable_region_yields():
    """40 regions, the first 5 within reach (region 3 yields 1 attempt in 10), the rest out of reach: round robin
    spends 7 of 8 attempts out of reach, the chooser returns to the 5 after one round."""
    counts = {}
    for chooser in (False, True):
        runs = []
        for seed in range(20):
            source = Rack(_regions(40), near=5, rate=[0.0, 0.0, 0.0, 0.1, 0.0], give_up_after=10**6)
            if chooser:
                source.chooser = StagedBandit(source.stats, source.hopeless_reasons)
            rng = np.random.default_rng(seed)
            while not source.draw(1, rng, never()):
                pass
            runs.append(source.total_attempts)
        counts[chooser] = np.median(runs)
    assert counts[True] < counts[False] / 2  # measured: median 36 against 84


def test_cover_sets_the_chooser_only_on_a_source_with_hopeless_reasons_and_consecutive_never():
    for strategy, hopeless, chosen in (("cover", ("out of reach",), True), ("consecutive", ("out of reach",), False),
                                       ("cover", (), False)):
        world = BoxWorld(WALLS)
        source = Rack(_regions(4), near=4, rate=[0.0] * 4)
        source.hopeless_reasons = hopeless
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=5, algorithm="bidirectional",
                                   strategy=strategy)
        solve(SPACE, world, source, START, settings, np.random.default_rng(0), seed=0)
        assert (source.chooser is not None) == chosen


def test_progress_holds_the_ik_allowance():
    free, rate = Cover.ik_free_attempts, Cover.ik_attempts_per_iteration
    c = Cover()
    assert c.region_chooser(Rack(_regions(3), near=3, rate=[0.0] * 3)) is not None
    c.add([0, 1])
    assert c.ik_allowance(10) == free + 10 * rate  # nothing progressed yet
    c.reward(0)
    assert c.ik_allowance(110) == free + 10 * rate  # sample 0 progressing
    c.penalize(0)
    assert c.ik_allowance(120) == free + 20 * rate


def test_without_a_chosen_order_the_allowance_is_the_plain_one():
    """A parking source (no hopeless reasons): round robin, and the budget per iteration whatever the progress."""
    c = Cover()
    source = Rack(_regions(3), near=3, rate=[0.0] * 3)
    source.hopeless_reasons = ()
    assert c.region_chooser(source) is None
    c.add([0])
    c.reward(0)
    assert c.ik_allowance(100) == Cover.free_attempts + 100 * Cover.attempts_per_iteration


def test_deferred_regions_wait_for_the_others_head_start_then_go_after_them():
    """Regions whose hand cannot back out (lazyground.drake.approach) get no attempt while a region without a usable
    sample that is not deferred has had fewer than DEFER; then they come after those of their stage (an order only)."""
    b = StagedBandit([RegionStats() for _ in range(5)], ("out of reach",), deferred=(0, 1))
    assert b.block(list(range(5))) == [2, 3, 4]
    for _ in range(DEFER):  # the others miss DEFER times each: the deferred join, after them
        for j in (2, 3, 4):
            b.observe(j, False, False)
    assert b.block(list(range(5))) == [2, 3, 4, 0, 1]
    b.observe(2, True, False)  # a region with a usable sample goes last, deferred or not
    assert b.block(list(range(5))) == [3, 4, 0, 1, 2]
    c = StagedBandit([RegionStats() for _ in range(3)], ("out of reach",), deferred=(0,))
    c.observe(1, True, False)
    c.observe(2, True, False)
    assert c.block([0, 1, 2]) == [0, 1, 2]  # no head start left to give: the deferred region without a sample first
    assert StagedBandit([RegionStats() for _ in range(3)], ("out of reach",)).block([0, 1, 2]) == [0, 1, 2]


def test_cover_hands_the_sources_blocked_approaches_to_its_chooser():
    source = Rack(_regions(4), near=4, rate=[0.0] * 4)
    source.blocked_approaches = lambda: frozenset({0, 2})
    chooser = Cover().region_chooser(source)
    assert list(chooser.deferred) == [True, False, True, False]
    assert chooser.block([0, 1, 2, 3]) == [1, 3]



def _one_region_ahead(memo=True):
    """40 regions, none yielding; the chooser defers all but region 0, which may take 4 attempts."""
    source = Rack(_regions(40), near=5, rate=[0.0] * 5, give_up_after=4)
    chooser = StagedBandit(source.stats, source.hopeless_reasons, deferred=range(1, 40))
    asked = []
    block = chooser.block
    chooser.block = lambda open_: asked.append(len(open_)) or block(open_)
    if not memo:  # every block asked afresh, as before
        chooser.version = None
    source.chooser = chooser
    return source, asked


def test_a_plan_asks_the_chooser_again_only_once_its_counts_or_the_open_regions_changed():
    """A plan that passes over entries whose region is out of attempts appends the same block again and again (#33:
    ~300 sorts of the open regions a request on a 64-can Fetch rack, one distinct): the block is asked once per
    change, and the schedule is the one asking every time gives."""
    plans, asks = {}, {}
    for memo in (True, False):
        source, asks[memo] = _one_region_ahead(memo)
        plans[memo] = source.plan(0, 3 * BLOCK), list(source._schedule)
    assert plans[True] == plans[False] and [j for j, _ in plans[True][0]] == [0] * 4  # region 0 alone, 4 attempts
    assert len(asks[True]) == 1 and len(asks[False]) > 40
    source, asked = _one_region_ahead()
    source.plan(0, 3 * BLOCK)
    source.draw(1, np.random.default_rng(0), never())  # counts change: asked again past the schedule's end
    assert len(asked) >= 2
    source, _ = _one_region_ahead()
    assert source._next_block() == [0]
    source.chooser = StagedBandit(source.stats, source.hopeless_reasons)  # another chooser, at version 0 too: asked
    assert source._next_block() == list(range(BLOCK))


def test_a_draw_past_a_spent_stretch_of_the_schedule_goes_on_to_the_next_block():
    """Region 0's 4 attempts, then the 41 entries a plan passed over after them (region 0 out of attempts): once
    region 0 is given up, a plan from there passed only those and stopped empty, and the draw asked again until
    its stop. Now it goes on to the chooser's next block (the deferred regions)."""
    source, _ = _one_region_ahead()
    source.plan(0, 3 * BLOCK)
    calls = []
    stop = StopCondition(interrupt=lambda: calls.append(1) or len(calls) > 1000)
    source.draw(1, np.random.default_rng(0), stop)
    assert len(calls) <= 1000 and source.total_attempts > 4 and set(source.order[4:]) <= set(range(1, 40))
