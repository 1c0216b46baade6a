"""The GoalSource contract, run against every goal source (ConfigGoalSource, IKGoalSource)."""

from __future__ import annotations

import numpy as np
import pytest

from lazyground.planning.stop import FakeClock, StopCondition
from tests.contract.conftest import get_world, world_param

NEVER = StopCondition()  # goal sampling bounded by attempts, never by the clock

SOURCES = [world_param(n) for n in ("toy", "parking_1", "fetch_cans_1")]  # config, config, IK
N = 6


@pytest.fixture(params=SOURCES)
def w(request):
    return get_world(request.param)


def test_every_sample_is_valid_and_lies_in_its_region(w):
    source = w.goals("reachable")
    samples = source.draw(N, np.random.default_rng(0), NEVER)
    assert 0 < len(samples) <= N
    for s in samples:
        assert 0 <= s.region < len(source.regions)
        for q in (s.q, s.end):  # where the planner aims and where the path ends (after any approach)
            assert q.shape == (w.space.dim,) and w.space.within_bounds(q)
            assert w.checker.config_free(q)
        assert w.in_region(source, s), source.regions[s.region].id


def test_stats_count_every_attempt(w):
    source = w.goals("reachable")
    samples = source.draw(N, np.random.default_rng(1), NEVER)
    samples += source.draw(N, np.random.default_rng(2), NEVER)
    assert len(source.stats) == len(source.regions)
    assert sum(st.valid for st in source.stats) == len(samples)
    assert sum(st.attempts for st in source.stats) >= len(samples)
    for j, st in enumerate(source.stats):
        assert st.valid == sum(s.region == j for s in samples)
        assert st.attempts == st.valid + sum(st.failures.values())  # every failed attempt has a reason
    assert source.sample_time > 0.0


def test_equal_seeds_draw_equal_samples(w):
    a = w.goals("reachable").draw(N, np.random.default_rng(3), NEVER)
    b = w.goals("reachable").draw(N, np.random.default_rng(3), NEVER)
    c = w.goals("reachable").draw(N, np.random.default_rng(4), NEVER)
    assert [s.region for s in a] == [s.region for s in b]
    assert all(np.array_equal(x.q, y.q) and np.array_equal(x.end, y.end) for x, y in zip(a, b))
    assert not all(np.array_equal(x.q, y.q) for x, y in zip(a, c))  # the seed matters


def test_an_impossible_region_is_exhausted_and_yields_nothing(w):
    source = w.goals("impossible")
    rng = np.random.default_rng(5)
    assert not source.exhausted()  # nothing tried yet
    drawn = []
    for _ in range(100):  # far more rounds than any give-up count needs
        if source.exhausted():
            break
        drawn += source.draw(N, rng, NEVER)
    assert source.exhausted() and drawn == []
    assert all(st.valid == 0 and st.attempts > 0 for st in source.stats)
    attempts = sum(st.attempts for st in source.stats)
    assert source.draw(N, rng, NEVER) == [] and sum(st.attempts for st in source.stats) == attempts


def test_an_expired_deadline_draws_nothing(w):
    source = w.goals("reachable")
    assert source.draw(N, np.random.default_rng(6), StopCondition.after(0.0, clock=FakeClock())) == []  # a deadline already reached
