"""The planner contract: ``solve`` with the one-tree and the two-tree algorithm, on the toy world and on parking.

Every outcome is bounded by ``max_iterations`` and a seed; the time limit is never reached.
"""

from __future__ import annotations

import numpy as np
import pytest

from lazyground.planning import PlannerSettings, PlanStatus, path_is_valid, solve
from tests.contract.conftest import NO_CLOCK, colliding_config, get_world, world_param

ALGORITHMS = ["rrt", "bidirectional"]
WORLDS = [world_param(n) for n in ("toy", "parking_1")]
BUDGET = 20_000  # iterations: far above what the seeded solves below need (toy: hundreds; parking: a few thousand)
FINE = 100  # re-check returned paths at 1/100 of the planner's edge resolution (the planner itself uses 1/10)


@pytest.fixture(params=WORLDS)
def w(request):
    return get_world(request.param)


@pytest.fixture(params=ALGORITHMS)
def algorithm(request):
    return request.param


def settings_for(w, algorithm: str, **overrides) -> PlannerSettings:
    base = dict(step_size=w.step_size, edge_resolution=w.resolution, goal_bias=0.1, time_limit=NO_CLOCK,
                max_iterations=BUDGET, algorithm=algorithm)
    return PlannerSettings(**{**base, **overrides})


def plan(w, algorithm, seed, kind="reachable", start=None, **overrides):
    return solve(w.space, w.checker, w.goals(kind), w.start if start is None else start,
                 settings_for(w, algorithm, **overrides), np.random.default_rng(seed), seed=seed)


def test_a_solved_path_runs_from_the_start_to_its_goal_sample_and_passes_a_finer_recheck(w, algorithm):
    settings = settings_for(w, algorithm)
    for seed in range(3):
        res = plan(w, algorithm, seed)
        assert res.status is PlanStatus.SOLVED, res.message
        assert res.seed == seed and res.iterations <= settings.max_iterations
        assert np.array_equal(res.path[0], w.start)
        assert np.allclose(res.path[-1], res.goal.end)
        assert res.goal_region is res.regions[res.goal.region]
        assert all(w.space.within_bounds(q) for q in res.path)
        assert path_is_valid(w.space, w.checker, res.path, settings.resolution / FINE) == -1
        assert res.path_length == pytest.approx(w.space.path_length(res.path))


def test_the_same_seed_gives_the_same_path_and_another_seed_another(w, algorithm):
    a, b, c = plan(w, algorithm, 7), plan(w, algorithm, 7), plan(w, algorithm, 8)
    assert a.solved and b.solved and c.solved
    assert np.array_equal(a.path, b.path) and a.iterations == b.iterations
    assert not (a.path.shape == c.path.shape and np.array_equal(a.path, c.path))


def test_a_colliding_start_is_an_invalid_start(w, algorithm):
    start = colliding_config(w, np.random.default_rng(0))
    res = plan(w, algorithm, 0, start=start)
    assert res.status is PlanStatus.INVALID_START and res.path is None and res.iterations == 0
    assert "collides with" in res.message and res.seed == 0


def test_a_start_outside_the_limits_is_an_invalid_start(w, algorithm):
    start = w.space.upper + 1.0
    res = plan(w, algorithm, 0, start=np.where(w.space.wrap, 0.0, start))
    assert res.status is PlanStatus.INVALID_START and "limits" in res.message


def test_impossible_goals_are_no_valid_goal(w, algorithm):
    res = plan(w, algorithm, 0, kind="impossible")
    assert res.status is PlanStatus.NO_VALID_GOAL and res.path is None and res.goal_samples == []
    assert all(r.id in res.message for r in res.regions)  # names each region and why it failed
    assert res.seed == 0


@pytest.mark.parametrize("limit", [1, 25, 400])
def test_max_iterations_is_respected(algorithm, limit):
    w = get_world("toy")  # its pocket region has valid samples that no path reaches
    res = plan(w, algorithm, 0, kind="unreachable", max_iterations=limit)
    assert res.status is PlanStatus.TIMEOUT and res.path is None
    assert res.iterations == limit and str(limit) in res.message


def test_max_iterations_bounds_a_drake_world_too(algorithm):
    pytest.importorskip("pydrake")
    w = get_world("parking_1")
    res = plan(w, algorithm, 0, max_iterations=3)  # three steps of 2 m reach no spot from the lot's entry
    assert res.status is PlanStatus.TIMEOUT and res.iterations == 3
