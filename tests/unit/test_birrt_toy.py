"""The bidirectional variant (start tree + goal forest) on the 2-D toy world."""

from dataclasses import replace

import numpy as np
import pytest

from lazyground.planning import PlannerSettings, PlanStatus, path_is_valid, solve
from lazyground.planning.problem import GoalSample
from tests.unit.toy import INVALID, REACHABLE, SPACE, START, UNREACHABLE, WALLS, BoxWorld, goal_source
from tests.unit.toy import NO_CLOCK, SOLVE_BUDGET, TIMEOUT_BUDGET

BI = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, algorithm="bidirectional")


def run(regions, seed, settings=BI, walls=WALLS):
    world = BoxWorld(walls)
    return world, solve(SPACE, world, goal_source(world, regions), START, settings, np.random.default_rng(seed), seed=seed)


@pytest.mark.parametrize("strategy", ["reward-penalty", "consecutive", "random", "cover"])
def test_reaches_the_only_reachable_grounding(strategy):
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, algorithm="bidirectional", strategy=strategy)
    for seed in range(6):
        world, res = run([UNREACHABLE, INVALID, REACHABLE], seed, settings)
        assert res.solved, res.message
        assert res.goal_region.id == "open"
        assert REACHABLE.contains(res.path[-1]) and np.allclose(res.path[0], START)
        assert np.allclose(res.path[-1], res.goal.q)
        assert path_is_valid(SPACE, world, res.path, settings.resolution / 10) == -1
        assert np.linalg.norm(np.diff(res.path, axis=0), axis=1).max() <= settings.step_size + 1e-9


def test_the_pocket_goal_trees_are_penalised_and_more_samples_drawn():
    # Only the enclosed pocket: its subtrees keep hitting the walls, so reward-penalty resamples.
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=TIMEOUT_BUDGET, algorithm="bidirectional",
                               initial_goal_samples=4, resample_count=4)
    world, res = run([UNREACHABLE], 0, settings)
    assert res.status is PlanStatus.TIMEOUT
    assert res.resamplings >= 1 and len(res.goal_samples) == 4 + 4 * res.resamplings
    assert sum(s.penalties for s in res.goal_samples) > 0
    assert sum(s.attempts for s in res.goal_samples) == sum(s.rewards + s.penalties for s in res.goal_samples)


def test_keep_tree_returns_both_trees_start_first():
    world = BoxWorld(WALLS)
    res = solve(SPACE, world, goal_source(world, [REACHABLE]), START, BI, np.random.default_rng(2), keep_tree=True)
    assert res.solved
    nodes, parents, goal_side = res.tree
    assert len(nodes) == res.tree_size and np.allclose(nodes[0], START) and parents[0] == -1
    assert goal_side.any() and not goal_side[0]
    roots = np.flatnonzero(parents == -1)
    assert len(roots) == 1 + len(res.goal_samples)  # the start and one root per goal sample
    assert all(parents[i] < i for i in range(len(parents)) if parents[i] >= 0)


def test_same_seed_same_path():
    _, a = run([UNREACHABLE, REACHABLE], 7)
    _, b = run([UNREACHABLE, REACHABLE], 7)
    assert a.solved and np.array_equal(a.path, b.path)


def test_thin_obstacle_between_edge_checks_is_never_returned():
    thin = [(4.0, 0.0, 4.001, 10.0)]
    settings = PlannerSettings(step_size=2.0, edge_resolution=1.0, time_limit=NO_CLOCK, max_iterations=400, algorithm="bidirectional",
                               validation_factor=1000.0)  # rejects from ~1
    world = BoxWorld(thin)
    res = solve(SPACE, world, goal_source(world, [REACHABLE]), START, settings, np.random.default_rng(0))
    assert res.status is PlanStatus.TIMEOUT and res.invalid_paths_rejected >= 1


class _BadApproach:
    """A goal source whose samples end with an approach segment through a thin wall."""

    def __init__(self, inner):
        self.inner, self.regions, self.stats = inner, inner.regions, inner.stats

    def draw(self, n, rng, stop):
        return [GoalSample(s.q, s.region, final=s.q + np.array([0.0, -1.5])) for s in self.inner.draw(n, rng, stop)]

    def exhausted(self):
        return self.inner.exhausted()

    @property
    def sample_time(self):
        return self.inner.sample_time


@pytest.mark.parametrize("algorithm", ["rrt", "bidirectional"])
def test_a_failing_approach_segment_retires_its_sample(algorithm):
    # The approach from (8, 9) goes 1.5 down, through a thin wall at y = 8.2 the planner never sees.
    walls = WALLS + [(7.0, 8.2, 9.0, 8.2001)]
    world = BoxWorld(walls)
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=400, goal_bias=0.5, algorithm=algorithm,
                               validation_factor=1000.0)  # the first rejection comes at 100-200 iterations
    res = solve(SPACE, world, _BadApproach(goal_source(world, [REACHABLE])), START, settings, np.random.default_rng(1))
    assert res.status is PlanStatus.TIMEOUT
    assert res.invalid_paths_rejected >= 1


def test_keep_tree_without_any_valid_goal_is_a_planning_failure():
    # #20: the empty goal forest made the tree arrays float and '|' raised TypeError (exit 3 under --html)
    world = BoxWorld(WALLS)
    res = solve(SPACE, world, goal_source(world, [INVALID]), START, BI, np.random.default_rng(0), keep_tree=True)
    assert res.status is PlanStatus.NO_VALID_GOAL
    nodes, parents, goal_side = res.tree
    assert nodes.shape == (1, SPACE.dim) and parents.tolist() == [-1] and goal_side.dtype == bool


def test_start_tree_edges_are_checked_when_a_path_uses_them(monkeypatch):
    # A wall 0.1 thick, a fifth of a step: start-tree nodes and midpoints, checked alone, land on both sides
    # of it, and their edges cross it. The join checks those edges at the planner's resolution and
    # cuts the branch, so no path through the wall ever reaches the fine re-check.
    import lazyground.planning.birrt as birrt

    verdicts = []
    check = birrt.path_is_valid
    monkeypatch.setattr(birrt, "path_is_valid", lambda *a: verdicts.append(check(*a)) or verdicts[-1])
    walls = [(4.0, 0.0, 4.1, 8.0), (4.0, 9.0, 4.1, 10.0)]
    for seed in range(10):
        world, res = run([REACHABLE], seed, walls=walls)
        assert res.solved and res.invalid_paths_rejected == 0, (seed, res.message)
        assert path_is_valid(SPACE, world, res.path, BI.resolution) == -1
    assert any(v >= 0 for v in verdicts), "no start-tree edge crossed the wall: the test lost its point"


@pytest.mark.parametrize("algorithm", ["rrt", "bidirectional"])
def test_a_retired_sample_is_never_selected_again(algorithm, monkeypatch):
    # the world of test_a_failing_approach_segment_retires_its_sample: every sample's approach crosses the thin wall
    from lazyground.planning.search import Search

    events = []
    select, retire = Search.select, Search.retire
    monkeypatch.setattr(Search, "select", lambda self: events.append(("select", select(self))) or events[-1][1])
    monkeypatch.setattr(Search, "retire", lambda self, gi: events.append(("retire", gi)) or retire(self, gi))
    world = BoxWorld(WALLS + [(7.0, 8.2, 9.0, 8.2001)])
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=400, goal_bias=0.5, algorithm=algorithm,
                               validation_factor=1000.0)
    res = solve(SPACE, world, _BadApproach(goal_source(world, [REACHABLE])), START, settings, np.random.default_rng(1))
    retired = [gi for kind, gi in events if kind == "retire"]
    assert retired and all(isinstance(gi, int) and 0 <= gi < len(res.goal_samples) for gi in retired)
    gone = set()
    for kind, gi in events:
        if kind == "retire":
            gone.add(gi)
        else:
            assert gi not in gone


def test_only_paths_that_pass_at_the_planner_resolution_reach_the_fine_recheck(monkeypatch):
    # the goal trees' edges are checked in full as they grow and the start tree's in the join, at the planner's
    # resolution: a path the fine re-check sees passes that coarser check everywhere. Walls 0.1 thick, a fifth of
    # a step, just past the start (its first edges cross them) and further away
    from lazyground.planning.search import Search

    seen = []
    recheck = Search.first_invalid_segment
    monkeypatch.setattr(Search, "first_invalid_segment", lambda self, path: seen.append(path) or recheck(self, path))
    for x in (1.3, 4.0):
        walls = [(x, 0.0, x + 0.1, 8.0), (x, 9.0, x + 0.1, 10.0)]
        for seed in range(6):
            seen.clear()
            world, res = run([REACHABLE], seed, walls=walls)
            assert res.solved and seen
            assert all(path_is_valid(SPACE, world, path, BI.resolution) == -1 for path in seen), (x, seed)


def test_a_goal_turn_credits_the_selected_tree_by_its_own_step(monkeypatch):
    # each credit follows, in the same iteration, the selected goal tree's step: blocked (-1) is a penalty
    # (gap -1), a free step is judged by its gap to the start tree (>= 0)
    import lazyground.planning.birrt as birrt

    events = []
    extend, credit = birrt._extend, birrt._credit
    monkeypatch.setattr(birrt, "_extend", lambda s, tree, q, step, label=None: events.append(
        ("extend", s.iterations, tree is s.trees[1], extend(s, tree, q, step, label))) or events[-1][3])
    monkeypatch.setattr(birrt, "_credit", lambda s, gi, closest, gap: events.append(
        ("credit", s.iterations, gap)) or credit(s, gi, closest, gap))
    for seed in range(3):
        events.clear()
        run([UNREACHABLE, REACHABLE], seed, replace(BI, goal_bias=0.5))
        credits = [i for i, e in enumerate(events) if e[0] == "credit"]
        assert credits and any(events[i][2] < 0 for i in credits) and any(events[i][2] >= 0 for i in credits)
        for i in credits:
            kind, iteration, goal_tree, (_, b) = events[i - 1]
            assert kind == "extend" and iteration == events[i][1] and goal_tree, (seed, events[i - 1], events[i])
            assert (events[i][2] < 0) == (b < 0)
