"""The ValidityChecker contract, run against every collision checker (toy world, DrakeWorld)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.contract.conftest import blocked_edge, colliding_config, free_edges, get_world, world_param

CHECKERS = [world_param(n) for n in ("toy", "parking_1", "fetch_cans_1")]
FINE = 10  # "a finer resolution": the planner's own re-check factor


@pytest.fixture(params=CHECKERS)
def w(request):
    return get_world(request.param)


def test_config_free_agrees_with_configs_free(w):
    rng = np.random.default_rng(0)
    qs = np.vstack([w.start, colliding_config(w, rng)] + [w.space.sample(rng) for _ in range(40)])
    batch = w.checker.configs_free(qs)
    assert batch.dtype == bool and batch.shape == (len(qs),)
    assert list(batch) == [w.checker.config_free(q) for q in qs]
    assert batch[0] and not batch[1]  # the start is free; the sampled collision is not
    assert list(w.checker.configs_free(qs[1])) == [False]  # one configuration as a 1-D array


def test_a_free_edge_is_free_at_a_finer_resolution_and_wholly_measured(w):
    for a, b in free_edges(w, np.random.default_rng(1), 8, w.step_size):
        fine = w.space.discretize(a, b, w.resolution / FINE)
        assert np.all(w.checker.configs_free(fine)), (a, b)
        assert w.checker.edge_fraction(a, b, w.resolution) == 1.0


def test_a_zero_length_edge_is_its_configuration(w):
    q = colliding_config(w, np.random.default_rng(2))
    assert w.checker.edge_free(w.start, w.start, w.resolution)
    assert not w.checker.edge_free(q, q, w.resolution)


def test_a_blocked_edge_measures_less_than_one_and_its_prefix_is_free(w):
    rng = np.random.default_rng(3)
    for _ in range(5):
        a, b = blocked_edge(w, rng)
        assert not w.checker.edge_free(a, b, w.resolution)
        t = w.checker.edge_fraction(a, b, w.resolution)
        assert 0.0 <= t < 1.0
        if t > 0:  # the free prefix a -> a + t (b - a), checked at the checker's own resolution
            prefix = w.space.interpolate(a, b, t)
            assert w.checker.edge_free(a, prefix, w.resolution)
            assert np.all(w.checker.configs_free(w.space.discretize(a, prefix, w.resolution)))


def test_edges_are_checked_no_coarser_than_asked(w):
    # An edge whose only colliding configurations sit between coarse checkpoints: the coarse
    # check may miss them, but a check at the fine resolution must not.
    rng = np.random.default_rng(4)
    q = colliding_config(w, rng)
    for _ in range(200):  # a free neighbour of q, one planner step away
        a, _ = w.space.steer(q, w.space.sample(rng), w.step_size)
        if w.checker.config_free(a):
            break
    else:
        pytest.fail("no free neighbour of a colliding configuration")
    b = w.space.interpolate(a, q, 2.0)  # q is the edge's midpoint
    assert not w.checker.edge_free(a, b, w.resolution / FINE)


def test_explain_names_a_colliding_pair_in_one_line(w):
    q = colliding_config(w, np.random.default_rng(5))
    why = w.checker.explain(q)
    assert "collides with" in why and "\n" not in why


def test_check_time_grows_monotonically(w):
    rng = np.random.default_rng(6)
    times = [w.checker.check_time]
    for _ in range(5):
        w.checker.config_free(w.space.sample(rng))
        times.append(w.checker.check_time)
        w.checker.configs_free(np.vstack([w.space.sample(rng) for _ in range(3)]))
        times.append(w.checker.check_time)
        a = w.space.sample(rng)
        w.checker.edge_free(a, w.space.steer(a, w.space.sample(rng), w.step_size)[0], w.resolution)
        times.append(w.checker.check_time)
    assert times[0] >= 0.0 and all(t1 >= t0 for t0, t1 in zip(times, times[1:]))
    assert times[-1] > times[0]
