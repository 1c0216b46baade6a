"""Issue #33: goal trees that stay their root are blocked, trees that take many steps without connecting age
(planning/blocked.py): their region counts the sample as a miss, and while no goal tree can grow cover's goal sampling is paced at its blocked rate (Cover.ik_allowance)."""

import numpy as np

import lazyground.planning.search as search_module
from lazyground.goals import ConfigGoalSource
from lazyground.planning import PlannerSettings, solve
from lazyground.planning.blocked import BlockedTrees
from lazyground.planning.cover import Cover
from lazyground.planning.problem import RegionStats
from lazyground.planning.region_bandit import StagedBandit
from lazyground.planning.search import path_is_valid
from tests.unit.test_region_bandit import Rack, _regions
from tests.unit.toy import NO_CLOCK, SPACE, START, WALLS, BoxWorld, region


def test_a_tree_is_blocked_after_its_steps_all_collide_and_live_again_when_it_grows():
    b = BlockedTrees(3)
    b.add()
    b.add()
    assert b.live == 2
    for _ in range(2):
        b.step(0, False)
    assert b.live == 2 and not b.blocked(0)
    b.step(0, False)  # the third collided step
    assert b.blocked(0) and b.live == 1
    b.step(0, False)
    assert b.live == 1
    b.step(0, True)  # it grows after all
    assert b.live == 2 and not b.blocked(0)


def test_the_chooser_hears_when_a_tree_becomes_blocked_and_when_it_grows_again():
    heard = []
    b = BlockedTrees(2, lambda gi, blocked: heard.append((gi, blocked)))
    b.add()
    b.add()
    b.step(1, False)
    assert heard == []
    b.step(1, False)
    b.step(1, False)
    assert heard == [(1, True)]
    b.step(1, True)
    b.step(0, True)  # grew without being blocked: nothing to tell
    assert heard == [(1, True), (1, False)]


def test_a_region_whose_sample_is_blocked_goes_back_among_those_without_one():
    b = StagedBandit([RegionStats() for _ in range(3)], ("out of reach",))
    for j, valid in ((0, True), (1, False), (2, False)):
        b.observe(j, valid, False)
    assert b.block([0, 1, 2])[-1] == 0  # a region with a sample last
    b.block_sample(0, True)
    assert b.block([0, 1, 2]) == [0, 1, 2]  # its blocked sample counts as a miss: tried once each, in order
    b.block_sample(0, False)
    assert b.block([0, 1, 2])[-1] == 0


def test_a_tree_that_grew_is_never_blocked_and_retiring_counts_once():
    b = BlockedTrees(2)
    b.add()
    b.add()
    b.step(0, True)
    for _ in range(5):
        b.step(0, False)
    assert b.live == 2
    b.retire(0)
    b.retire(0)
    assert b.live == 1
    b.step(1, False)
    b.step(1, False)
    b.retire(1)  # blocked already: not live
    assert b.live == 0


def test_while_no_tree_can_grow_the_allowance_earns_the_blocked_rate():
    c = Cover()
    assert c.region_chooser(Rack(_regions(3), near=3, rate=[0.0] * 3)) is not None
    free, rate, blocked = Cover.ik_free_attempts, Cover.ik_attempts_per_iteration, Cover.ik_blocked_attempts_per_iteration
    assert blocked > rate
    assert c.ik_allowance(10, growing=False) == free + 10 * blocked
    assert c.ik_allowance(30, growing=True) == free + 10 * blocked + 20 * rate
    c.add([0])
    c.reward(0)  # a tree progressing holds goal sampling, unless none can grow
    assert c.ik_allowance(40, growing=True) == free + 10 * blocked + 20 * rate
    assert c.ik_allowance(50, growing=False) == free + 20 * blocked + 20 * rate


class Cells(ConfigGoalSource):
    hopeless_reasons = ("out of reach",)  # (an IK source's: cover chooses the regions)


# a goal cell walled in on every side closer than a step: its samples are valid, every step out of them collides
CELL = WALLS + [(1.6, 4.6, 2.4, 4.7), (1.6, 5.3, 2.4, 5.4), (1.6, 4.6, 1.7, 5.4), (2.3, 4.6, 2.4, 5.4)]
OPEN = region("open", 8.0, 9.0)
CELLS = [region(f"cell{k}", 2.0, 5.0, half=0.05) for k in range(6)]


def _record_trees(monkeypatch) -> list:
    """The BlockedTrees each search makes, in order."""
    made = []

    class Recorded(BlockedTrees):
        def __init__(self, *args):
            super().__init__(*args)
            made.append(self)

    monkeypatch.setattr(search_module, "BlockedTrees", Recorded)
    return made


def test_cover_finds_the_walled_cells_trees_blocked_and_still_solves(monkeypatch):
    made = _record_trees(monkeypatch)
    solved = 0
    for seed in range(6):
        world = BoxWorld(CELL)
        source = Cells(tuple(CELLS + [OPEN]), SPACE, world)
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=3000, algorithm="bidirectional",
                                   strategy="cover")
        r = solve(SPACE, world, source, START, settings, np.random.default_rng(seed), seed=seed)
        b = made[-1]
        kinds = [source.regions[g.region].id == "open" for g in r.goal_samples]
        assert any(b.blocked(i) for i, is_open in enumerate(kinds) if not is_open)  # a cell's tree was blocked
        assert not any(b.blocked(i) for i, is_open in enumerate(kinds) if is_open)  # the open region's never
        assert b.live == sum(not b.blocked(i) and b.fails[i] != -2 for i in range(len(kinds)))
        if r.solved:
            solved += 1
            assert path_is_valid(SPACE, world, r.path, settings.resolution / 10) < 0
            assert source.regions[r.goal.region].id == "open"
    assert solved == 6


def test_no_blocked_trees_without_a_chosen_order_nor_in_the_one_tree_planner(monkeypatch):
    made = []
    monkeypatch.setattr(search_module, "BlockedTrees", lambda *a: made.append(a) or BlockedTrees(*a))
    for strategy, algorithm in (("reward-penalty", "bidirectional"), ("consecutive", "bidirectional"),
                                ("cover", "rrt")):
        world = BoxWorld(CELL)
        source = Cells(tuple(CELLS + [OPEN]), SPACE, world)
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=50, algorithm=algorithm,
                                   strategy=strategy)
        solve(SPACE, world, source, START, settings, np.random.default_rng(0), seed=0)
    assert made == []


def test_a_tree_that_grows_ages_after_its_steps_once_and_for_all():
    heard = []
    b = BlockedTrees(2, None, age_after=4, on_age=heard.append)
    b.add()
    b.add()
    b.step(0, True)
    for _ in range(2):
        b.step(0, False)
    assert b.live == 2 and not b.aged(0)
    b.step(0, True)  # its fourth step
    assert b.aged(0) and b.live == 1 and heard == [0]
    b.step(0, True)  # an aged tree stays aged, heard of once
    b.retire(0)
    assert b.live == 1 and heard == [0]
    for _ in range(4):  # sample 1: blocked after 2 collided steps, then aged: not live either way, told only once
        b.step(1, False)
    assert b.aged(1) and b.live == 0 and heard == [0]


def test_no_aging_without_age_after():
    b = BlockedTrees(2)
    b.add()
    for _ in range(10_000):
        b.step(0, True)
    assert b.live == 1 and not b.aged(0)


def test_an_aged_samples_region_goes_back_among_those_without_one_ahead_of_those_that_never_yielded():
    b = StagedBandit([RegionStats() for _ in range(3)], ("out of reach",))
    for _ in range(4):
        b.observe(0, False, False)
    b.observe(0, True, False)  # region 0: 5 attempts, one valid sample
    b.observe(1, False, False)
    b.observe(2, False, False)
    assert b.block([0, 1, 2])[-1] == 0
    b.age_sample(0)
    assert b.block([0, 1, 2])[0] == 0  # its next attempt: it does yield (a blocked sample would count as a miss)
    b2 = StagedBandit([RegionStats() for _ in range(3)], ("out of reach",))
    for j in (0, 0, 0, 0):
        b2.observe(j, False, False)
    b2.observe(0, True, False)
    b2.observe(1, False, False)
    b2.observe(2, False, False)
    b2.block_sample(0, True)
    assert b2.block([0, 1, 2])[0] == 1  # (the difference: a blocked sample's region is scored as a miss)


POCKET = region("pocket", 8.0, 2.0)  # inside the toy's walled pocket: its tree grows inside and never gets out


def test_cover_ages_the_pocket_trees_and_still_solves(monkeypatch):
    made = _record_trees(monkeypatch)
    monkeypatch.setattr(Cover, "age_after", 20)
    monkeypatch.setattr(StagedBandit, "age_sample", lambda self, j: heard.append(j))
    solved = aged = told = 0
    for seed in range(6):
        heard = []
        world = BoxWorld(WALLS)
        source = Cells((POCKET, POCKET, POCKET, OPEN), SPACE, world)
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=4000, algorithm="bidirectional",
                                   strategy="cover")
        r = solve(SPACE, world, source, START, settings, np.random.default_rng(seed), seed=seed)
        b = made[-1]
        assert b.age_after == 20
        pocket = [i for i, g in enumerate(r.goal_samples) if source.regions[g.region].id == "pocket"]
        aged += any(b.aged(i) for i in pocket)
        aged_samples = [i for i in range(len(b.fails)) if b.aged(i)]
        assert set(heard) <= {r.goal_samples[i].region for i in aged_samples} and len(heard) <= len(aged_samples)
        told += len(heard)
        assert b.live == sum(b.is_live(i) for i in range(len(r.goal_samples)))
        if r.solved:
            solved += 1
            assert path_is_valid(SPACE, world, r.path, settings.resolution / 10) < 0
            assert source.regions[r.goal.region].id == "open"
    assert solved == 6 and aged >= 3 and told > 0  # (the chooser hears of the samples that aged while live)
