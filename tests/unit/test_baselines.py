"""The bench's baselines (issue #33) on the toy world: what each does with a reachable region, a pocket
(valid samples, enclosed) and a region without valid samples. Bounded by iterations, not the clock."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from lazyground.bench.baselines import run_baseline
from lazyground.settings import PlannerSettings
from tests.unit.toy import INVALID, NO_CLOCK, REACHABLE, SPACE, START, UNREACHABLE, WALLS, BoxWorld


class World(BoxWorld):
    space = SPACE
    start = START


def _scene(regions):
    objects = [SimpleNamespace(id=r.object, pose=SimpleNamespace(xyz=((r.lower[0] + r.upper[0]) / 2, (r.lower[1] + r.upper[1]) / 2, 0.0)))
               for r in regions]
    return SimpleNamespace(robot=SimpleNamespace(model="car"), objects=objects)


def _run(name, regions, seed=0, cap=3000, algorithm="bidirectional"):
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=cap, algorithm=algorithm)
    return run_baseline(name, _scene(regions), World(WALLS), tuple(regions), SPACE, settings, seed, call_budget=NO_CLOCK)


@pytest.mark.parametrize("seed", range(3))
def test_nearest_first_spends_a_whole_call_on_the_nearer_pocket(seed):
    result, _, iterations, _ = _run("nearest-first", (REACHABLE, UNREACHABLE), seed)
    assert result.solved and result.goal_region.id == "open"
    assert iterations > 3000  # the pocket (nearer the start) had its call first, to the cap


def test_multiplexer_sticks_to_the_first_region_that_yields_samples():
    result, *_ = _run("multiplexer", (UNREACHABLE, REACHABLE))
    assert not result.solved and {s.region for s in result.goal_samples} == {0}
    result, *_ = _run("multiplexer", (INVALID, REACHABLE))  # the first is given up: on to the next
    assert result.solved and result.goal_region.id == "open"


def test_eager_samples_every_region_first():
    result, _, _, attempts = _run("eager", (INVALID, UNREACHABLE, REACHABLE))
    assert result.solved and result.goal_region.id == "open"
    assert {s.region for s in result.goal_samples} == {1, 2}
    assert result.region_stats[0].attempts >= 50  # the invalid region was tried until given up, before planning


@pytest.mark.parametrize("algorithm", ["rrt", "bidirectional"])
def test_independent_planners_take_turns_and_stop_at_the_first_solution(algorithm):
    solved = [_run("independent", (UNREACHABLE, INVALID, REACHABLE), seed, cap=20000, algorithm=algorithm)[0] for seed in range(2)]
    assert all(r is not None and r.solved and r.goal_region.id == "open" for r in solved)


def test_nearest_first_counts_its_budgets_and_total_on_the_stop_clock(monkeypatch):
    """The per-call budget and the reported total both read the stop module's clock (a CPU or fake clock applies)."""
    from lazyground.planning import stop

    clock = stop.FakeClock(tick=1e-4)
    monkeypatch.setattr(stop, "CLOCK", clock)
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=10**6, algorithm="bidirectional")
    t0 = clock.t
    result, seconds, iterations, _ = run_baseline("nearest-first", _scene((REACHABLE, UNREACHABLE)), World(WALLS),
                                                  (REACHABLE, UNREACHABLE), SPACE, settings, 0, call_budget=0.5)
    assert result.solved and iterations < 10**6  # the pocket's call ended at its 0.5 s on the fake clock
    assert seconds >= 0.5 and abs(seconds - (clock.t - t0)) < 1e-3
