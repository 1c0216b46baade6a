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


def _short_obstacle_crossings(w, rng, lines: int = 60, keep: int = 10) -> list[tuple[np.ndarray, np.ndarray, float]]:
    """Edges (a, b, run) with free ends and a colliding middle of length ``run`` just above the resolution,
    the shortest ``keep`` found by sampling finely along seeded random lines."""
    fine, found = w.resolution / FINE, []
    for _ in range(lines):
        a = w.space.sample(rng)
        b, _ = w.space.steer(a, w.space.sample(rng), 4 * w.step_size)
        qs = w.space.discretize(a, b, fine)
        free = w.checker.configs_free(qs)
        edges = np.flatnonzero(np.diff(free.astype(int)))  # k: free[k] != free[k + 1]
        for k0, k1 in zip(edges[:-1], edges[1:]):
            if free[k0] and not free[k0 + 1]:  # a colliding run qs[k0 + 1 .. k1] between free qs[k0], qs[k1 + 1]
                run = w.space.distance(qs[k0 + 1], qs[k1])
                if run > 1.2 * w.resolution:
                    found.append((qs[k0], qs[k1 + 1], run))
    assert found, f"{w.name}: no obstacle crossing found"
    return sorted(found, key=lambda e: e[2])[:keep]


def test_edges_are_checked_no_coarser_than_asked(w):
    # A colliding stretch longer than the resolution between two free ends: checks no more than
    # `resolution` apart must land in it, however the checker places them.
    for a, b, run in _short_obstacle_crossings(w, np.random.default_rng(4)):
        assert w.checker.config_free(a) and w.checker.config_free(b)
        assert not w.checker.edge_free(a, b, w.resolution), f"missed a {run:.3g} long collision"
        assert w.checker.edge_fraction(a, b, w.resolution) < 1.0


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
