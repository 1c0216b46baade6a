"""The RRT of Algorithm 1 on a 2-D toy world with a fake checker."""

from dataclasses import replace

import numpy as np
import pytest

from lazyground.planning import PlannerSettings, PlanStatus, path_is_valid, solve
from lazyground.planning.stop import FakeClock, StopCondition, StopReason
from tests.unit.toy import INVALID, REACHABLE, SPACE, START, UNREACHABLE, WALLS, BoxWorld, goal_source, region
from tests.unit.toy import NO_CLOCK, SOLVE_BUDGET, TIMEOUT_BUDGET

SETTINGS = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, goal_bias=0.1)


def run(regions, seed, settings=SETTINGS, walls=WALLS, start=START, stop=None):
    world = BoxWorld(walls)
    return world, solve(SPACE, world, goal_source(world, regions), start, settings, np.random.default_rng(seed), seed=seed,
                        stop=stop)


@pytest.mark.parametrize("strategy", ["reward-penalty", "consecutive", "random"])
def test_reaches_the_only_reachable_grounding(strategy):
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, goal_bias=0.1, strategy=strategy)
    solved = 0
    for seed in range(8):
        world, res = run([UNREACHABLE, INVALID, REACHABLE], seed, settings)
        if res.solved:
            solved += 1
            assert res.goal_region.id == "open"
            assert REACHABLE.contains(res.path[-1])
            assert np.allclose(res.path[0], START)
            # re-check at a tenth of the planner's edge resolution
            assert path_is_valid(SPACE, world, res.path, settings.resolution / 10) == -1
            steps = np.linalg.norm(np.diff(res.path, axis=0), axis=1)
            assert steps.max() <= settings.step_size + 1e-9
            assert res.seed == seed
    assert solved >= 7


def test_result_records_counts_and_time_split():
    world, res = run([UNREACHABLE, REACHABLE], 3)
    assert res.solved
    assert res.iterations > 0 and res.tree_size >= len(res.path)
    assert len(res.goal_samples) >= 10
    assert sum(s.attempts for s in res.goal_samples) == sum(s.rewards + s.penalties for s in res.goal_samples)
    assert res.collision_s > 0 and res.goal_sampling_s > 0
    assert res.time_s >= res.collision_s + res.goal_sampling_s - 1e-9
    pocket = [s for s in res.goal_samples if res.regions[s.region].id == "pocket"]
    assert pocket and all(s.rewards == 0 or s.penalties > 0 for s in pocket)


class CountingWorld(BoxWorld):
    """The toy world on a check clock: each configuration checked costs one 'second'."""

    @property
    def check_time(self) -> float:
        return float(self.checks)


def test_collision_time_and_count_leave_out_every_goal_draws_checks():
    # on the check clock, the search's collision seconds are its collision checks, one for one, however many draws
    settings = replace(SETTINGS, initial_goal_samples=1, resample_count=1)  # one sample per draw: many draws
    resamplings = 0
    for seed in range(3):
        world = CountingWorld(WALLS)
        res = solve(SPACE, world, goal_source(world, [UNREACHABLE, REACHABLE]), START, settings, np.random.default_rng(seed))
        assert 0 < res.collision_checks < world.checks  # the draws' checks are left out
        assert res.collision_s == res.collision_checks
        resamplings += res.resamplings
    assert resamplings >= 2
    # a second plan on the same world and goal source counts only its own checks and goal-sampling time
    goals = goal_source(world, [UNREACHABLE, REACHABLE])
    solve(SPACE, world, goals, START, settings, np.random.default_rng(0))
    checks, sampling = world.checks, goals.sample_time
    res = solve(SPACE, world, goals, START, settings, np.random.default_rng(1))
    assert 0 < res.collision_checks < world.checks - checks and res.collision_s == res.collision_checks
    assert 0 <= res.goal_sampling_s <= goals.sample_time - sampling


def test_the_strategy_resamples_at_the_planners_threshold():
    # threshold 0.6: a penalty takes any weight (at most 1) to at most 0.5, below it, so every penalty of the
    # one-tree planner asks for more samples (the default 0.2 takes four penalties from 1)
    settings = replace(SETTINGS, goal_bias=0.5, resample_threshold=0.6, max_iterations=300)
    world, res = run([UNREACHABLE], 0, settings)
    penalties = sum(s.penalties for s in res.goal_samples)
    assert penalties > 0 and res.resamplings == penalties


def test_reward_penalty_penalises_unreachable_samples_and_resamples():
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, goal_bias=0.5, initial_goal_samples=4, resample_count=4)
    world, res = run([UNREACHABLE], 0, replace(settings, max_iterations=TIMEOUT_BUDGET))
    assert res.status is PlanStatus.TIMEOUT
    assert res.resamplings >= 1
    assert len(res.goal_samples) == 4 + 4 * res.resamplings


def test_an_iteration_limit_is_named_as_such():
    # audit8: max_iterations=5 said "no path within 10 s (5 iterations)" after a few milliseconds
    world, res = run([UNREACHABLE], 0, PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=5))
    assert res.status is PlanStatus.TIMEOUT and res.message.startswith("no path within 5 iterations (max_iterations);")


def test_a_one_tree_timeout_says_what_to_try():
    # issue 34: the README's `--algorithm rrt` line timed out after 31 s with no hint that the default planner solves it
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=5)
    _, res = run([UNREACHABLE], 0, settings)
    assert res.status is PlanStatus.TIMEOUT and res.message.endswith("try --algorithm bidirectional")
    _, res = run([UNREACHABLE], 0, replace(settings, algorithm="bidirectional"))
    assert res.status is PlanStatus.TIMEOUT and res.message == "no path within 5 iterations (max_iterations)"


def test_same_seed_same_path():
    _, a = run([UNREACHABLE, REACHABLE], 11)
    _, b = run([UNREACHABLE, REACHABLE], 11)
    assert a.solved and b.solved
    assert np.array_equal(a.path, b.path)
    _, c = run([UNREACHABLE, REACHABLE], 12)
    assert not (len(c.path) == len(a.path) and np.array_equal(c.path, a.path))


def test_invalid_start():
    world, res = run([REACHABLE], 0, start=np.array([4.5, 4.0]))
    assert res.status is PlanStatus.INVALID_START
    assert "collision" in res.message and res.path is None


def test_start_outside_limits():
    world, res = run([REACHABLE], 0, start=np.array([-1.0, 4.0]))
    assert res.status is PlanStatus.INVALID_START and "limits" in res.message


def test_no_valid_goal_names_each_region():
    world, res = run([INVALID], 0)
    assert res.status is PlanStatus.NO_VALID_GOAL
    assert res.message == "no valid goal configuration in any goal region: block: 50 configurations tried, 0 valid (in collision x50)"


def fake_stop(settings: PlannerSettings) -> StopCondition:
    """The settings' limits on a clock that advances 1 ms per reading, whatever the machine's load."""
    return StopCondition.after(settings.time_limit, max_iterations=settings.max_iterations, clock=FakeClock(tick=1e-3))


@pytest.mark.parametrize("algorithm", ["rrt", "bidirectional"])
def test_a_limit_reached_before_every_region_was_tried_is_a_timeout(algorithm):
    # audit8: "--time-limit 0.001" on fetch_cans_1 said no_valid_goal ("no valid goal configuration in any
    # goal region"), with 11 of 12 regions "not tried": the limit ended goal sampling, not the regions
    settings = PlannerSettings(time_limit=0.01, algorithm=algorithm)
    world, res = run([INVALID], 0, settings, stop=fake_stop(settings))
    assert res.status is PlanStatus.TIMEOUT and res.path is None, res.message
    assert res.message.startswith("no valid goal configuration found within 0.01 s") and "block: " in res.message and "configurations tried, 0 valid" in res.message
    settings = PlannerSettings(time_limit=1.0, algorithm=algorithm)  # time to give up on the region
    world, res = run([INVALID], 0, settings, stop=fake_stop(settings))
    assert res.status is PlanStatus.NO_VALID_GOAL, res.message


def test_regions_a_limit_came_before_are_named_not_tried():
    # 1 ms on a clock that advances 1 ms per reading: over before the first goal-sampling attempt
    settings = PlannerSettings(time_limit=0.001)
    world, res = run([INVALID, region("block2", 8.0, 6.75, half=0.5)], 0, settings, stop=fake_stop(settings))
    assert res.status is PlanStatus.TIMEOUT
    assert res.message.endswith(": block: not tried; block2: not tried"), res.message


def test_a_solved_result_has_an_empty_message():
    world, res = run([REACHABLE], 0)
    assert res.status is PlanStatus.SOLVED and res.message == ""


def test_timeout_respects_the_limit():
    # The time limit itself, on a fake clock: the planner stops at the first reading past the limit.
    settings = PlannerSettings(step_size=0.5, time_limit=0.3, goal_bias=0.1)
    stop = fake_stop(settings)
    world, res = run([UNREACHABLE], 0, settings, stop=stop)
    assert res.status is PlanStatus.TIMEOUT and res.path is None and stop.reason is StopReason.TIMEOUT
    assert settings.time_limit <= res.time_s <= settings.time_limit + 0.1  # a few readings past the limit
    assert 0 < res.iterations < 300  # at least one reading per iteration


def test_thin_obstacle_between_edge_checks_is_never_returned():
    # A wall thinner than the edge resolution: the planner's coarse edge checks can step
    # over it, the fine re-validation must not let such a path out.
    thin = [(4.0, 0.0, 4.001, 10.0)]
    settings = PlannerSettings(step_size=2.0, edge_resolution=1.0, time_limit=NO_CLOCK, max_iterations=400, goal_bias=0.3, validation_factor=1000.0)  # rejects from ~10
    world = BoxWorld(thin)
    goals = goal_source(world, [REACHABLE])
    res = solve(SPACE, world, goals, START, settings, np.random.default_rng(0))
    assert res.status is PlanStatus.TIMEOUT
    assert res.invalid_paths_rejected >= 1


@pytest.mark.parametrize("mode,bias", [("extend", 0.1), ("partial", 0.5), ("connect", 0.1)])
def test_every_goal_extension_reaches_the_goal_and_stays_valid(mode, bias):
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, goal_bias=bias, goal_extension=mode)
    solved = 0
    for seed in range(5):
        world, res = run([UNREACHABLE, REACHABLE], seed, settings)
        if res.solved:
            solved += 1
            assert res.goal_region.id == "open"
            assert path_is_valid(SPACE, world, res.path, settings.resolution / 10) == -1
            assert np.linalg.norm(np.diff(res.path, axis=0), axis=1).max() <= settings.step_size + 1e-9
    assert solved >= 4


def test_partial_goal_step_keeps_its_free_part_and_is_rewarded():
    # Start (1, 1), goal sample in the pocket around (8, 2): the 5-unit goal step meets the
    # wall at x = 4. "partial" keeps the free part (the authors' RRTGoalRegion) and rewards
    # the sample; the next goal step from that node is blocked at once and is penalised.
    base = dict(step_size=5.0, edge_resolution=0.25, goal_bias=1.0, initial_goal_samples=1, goal_extension="partial")
    world, one = run([UNREACHABLE], 0, PlannerSettings(**base, max_iterations=1))
    assert one.tree_size == 2
    sample = one.goal_samples[0]
    assert (sample.attempts, sample.rewards, sample.penalties) == (1, 1, 0)
    world, two = run([UNREACHABLE], 0, PlannerSettings(**base, max_iterations=2))
    sample = two.goal_samples[0]
    assert two.tree_size == 2 and (sample.attempts, sample.rewards, sample.penalties) == (2, 1, 1)
    kept = solve(SPACE, BoxWorld(WALLS), goal_source(BoxWorld(WALLS), [UNREACHABLE]), START,
                 PlannerSettings(**base, max_iterations=1), np.random.default_rng(0), keep_tree=True).tree[0][1]
    assert 4.0 - 0.25 - 1e-9 <= kept[0] < 4.0  # the last free check before the wall
    assert world.config_free(kept)


def test_a_goal_step_blocked_at_once_is_not_checked_again_from_the_same_node():
    # Iteration 1 moves up to the wall (checked), iteration 2 is blocked at once (checked);
    # iterations 3-5 repeat that same edge: penalised again without another check.
    class Counting(BoxWorld):
        calls = 0

        def edge_fraction(self, a, b, resolution):
            Counting.calls += 1
            return super().edge_fraction(a, b, resolution)

    world = Counting(WALLS)
    settings = PlannerSettings(step_size=5.0, edge_resolution=0.25, goal_bias=1.0, initial_goal_samples=1,
                               resample_count=1, max_iterations=5)
    res = solve(SPACE, world, goal_source(world, [UNREACHABLE]), START, settings, np.random.default_rng(0))
    sample = res.goal_samples[0]
    assert (sample.attempts, sample.rewards, sample.penalties) == (5, 1, 4)
    assert Counting.calls == 2 and res.tree_size == 2


def test_a_rejected_goal_edge_is_not_rebuilt_from_the_same_node():
    # A wall thinner than the edge checks: the goal step from the start passes them, the fine
    # re-check rejects the path and cuts the new node. The start is still the goal sample's
    # nearest node, so the next goal step would be the very same edge: it must not be rebuilt
    # and re-checked (a livelock measured on fetch_boxes_3: 288 rejections of one edge in 30 s).
    thin = [(4.0, 0.0, 4.001, 10.0)]
    settings = PlannerSettings(step_size=20.0, edge_resolution=1.0, validation_factor=1000.0, goal_bias=1.0,
                               initial_goal_samples=1, resample_count=1, max_iterations=30)
    world = BoxWorld(thin)
    res = solve(SPACE, world, goal_source(world, [REACHABLE]), START, settings, np.random.default_rng(0))
    assert res.status is PlanStatus.TIMEOUT
    assert 1 <= res.invalid_paths_rejected <= len(res.goal_samples) < res.iterations
