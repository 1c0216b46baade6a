"""The cover strategy (issue #33): reward-penalty weights on a lazy heap, coverage paced by the search."""

from __future__ import annotations

import numpy as np

from lazyground.planning import PlannerSettings, solve
from lazyground.planning.cover import Cover
from lazyground.planning.strategies import RewardPenalty
from lazyground.regions import ConfigRegion
from tests.unit.toy import NO_CLOCK, REACHABLE, SPACE, START, UNREACHABLE, WALLS, BoxWorld, goal_source


def test_weights_follow_reward_penalty_without_the_reset():
    c, rp = Cover(), RewardPenalty()
    c.add([0, 1]), rp.add([0, 1])
    for sel in (c, rp):
        assert sel.select(None) == 0
        sel.penalize(0)
        assert sel.select(None) == 1 and sel.weight(0) == 0.5
    c.add([2]), rp.add([2])
    assert c.weight(0) == 0.5 and c.weight(1) == 1.0  # the old weights stay
    assert rp.weight(1) == 0.5  # reward-penalty resets them
    assert [c.penalize(1) for _ in range(5)] == [False] * 4 + [True]  # 1 -> .5 -> .33 -> .25 -> .2 -> .17, below 0.2
    assert c.select(None) == 2 and c.batch == 1


def _regions(n):
    """n small pockets (valid samples, enclosed) in a row, and the open region last."""
    return [ConfigRegion(id=f"p{i}", interpretation=f"go:p{i}", object=f"p{i}", lower=(7.9, 1.9), upper=(8.1, 2.1))
            for i in range(n)] + [REACHABLE]


def test_cover_samples_every_region_once_paced_by_iterations():
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=20_000, algorithm="bidirectional",
                               strategy="cover", initial_goal_samples=2)
    regions = _regions(30)
    solved = []
    for seed in range(3):
        world = BoxWorld(WALLS)
        res = solve(SPACE, world, goal_source(world, regions), START, settings, np.random.default_rng(seed), seed=seed)
        solved.append(res.solved and res.goal_region.id == "open")
        assert {s.region for s in res.goal_samples} >= ({30} if res.solved else set())
        assert len(res.goal_samples) <= len(regions) + res.iterations
    assert all(solved)


def test_reward_penalty_waits_for_the_open_region_longer_than_cover():
    # 30 pockets before the open region: reward-penalty gets to it only after resampling rounds
    iters = {}
    for strategy in ("reward-penalty", "cover"):
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=4_000, algorithm="bidirectional",
                                   strategy=strategy)
        runs = []
        for seed in range(3):
            world = BoxWorld(WALLS)
            res = solve(SPACE, world, goal_source(world, _regions(30)), START, settings, np.random.default_rng(seed), seed=seed)
            runs.append(res.iterations if res.solved else settings.max_iterations)
        iters[strategy] = np.median(runs)
    assert iters["cover"] < iters["reward-penalty"]


def test_cover_paces_goal_sampling_attempts_by_iterations():
    """Issue #33 (arm racks: ~1 % of IK attempts valid): coverage draws stop while the goal source's attempts
    exceed Cover.free_attempts plus Cover.attempts_per_iteration per iteration; before, every iteration
    could spend a whole draw's budget (10 attempts) on regions that never yield."""
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=600, algorithm="bidirectional",
                               strategy="cover", initial_goal_samples=2)
    regions = [REACHABLE] + [ConfigRegion(id=f"w{i}", interpretation=f"go:w{i}", object=f"w{i}", lower=(4.2, 0.5),
                                          upper=(4.8, 7.5)) for i in range(300)]  # in the wall: never valid
    for seed in range(2):
        world = BoxWorld(WALLS)
        source = goal_source(world, regions)
        res = solve(SPACE, world, source, START, settings, np.random.default_rng(seed), seed=seed)
        draw = source.attempts_per_sample  # a draw that starts within the budget may use its whole budget
        first = settings.initial_goal_samples * draw  # the first draw comes before the pacing
        assert source.total_attempts <= first + Cover.free_attempts + Cover.attempts_per_iteration * res.iterations + draw
        assert source.total_attempts > Cover.free_attempts  # and it does keep drawing

def test_cover_connect_credits_goal_trees_on_start_turns():
    """cover-connect: each new start-tree node is also a target for the strategy's goal tree, credited; the
    pockets' trees are penalised there too, and every run still reaches the open region along a valid path."""
    from lazyground.planning import path_is_valid

    credited = {}
    for strategy in ("cover", "cover-connect"):
        settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=4_000, algorithm="bidirectional",
                                   strategy=strategy)
        total = 0
        for seed in range(6):
            world = BoxWorld(WALLS)
            res = solve(SPACE, world, goal_source(world, _regions(30)), START, settings, np.random.default_rng(seed), seed=seed)
            assert res.solved and res.goal_region.id == "open"
            assert path_is_valid(SPACE, world, res.path, settings.resolution / 10) == -1
            total += sum(s.penalties + s.rewards for s in res.goal_samples)
        credited[strategy] = total
    assert credited["cover-connect"] > 2 * credited["cover"]
