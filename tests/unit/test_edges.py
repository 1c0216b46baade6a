"""Bisection-ordered edge checks (lazyground.motion.edges) on the toy world (no Drake)."""

import numpy as np

from lazyground.motion.edges import PROBES, bisected_edge, bisection_levels, probe_batches
from tests.unit.toy import SPACE, CountingWorld


def test_the_levels_hold_every_index_once_middle_first_ends_last():
    for n in range(1, 200):
        levels = bisection_levels(n)
        assert sorted(int(i) for level in levels for i in level) == list(range(n))
        assert sorted(levels[-1].tolist()) == ([0] if n == 1 else [0, n - 1])
        if n > 2:
            assert levels[0].tolist() == [(n - 1) // 2]


def test_the_batches_probe_levels_until_probes_then_take_the_rest_at_once():
    for n in range(1, 200):
        batches, levels = probe_batches(n), bisection_levels(n)
        assert sorted(int(i) for batch in batches for i in batch) == list(range(n))
        probed = np.cumsum([len(batch) for batch in batches])
        assert all(p < PROBES for p in probed[:-2])  # every batch but the last starts below PROBES probed
        assert all(np.array_equal(batch, level) for batch, level in zip(batches[:-1], levels))
        if n > 2:
            assert batches[0].tolist() == [(n - 1) // 2]  # the middle alone first


def test_it_answers_as_the_sequential_check_and_stops_early_on_a_collision():
    world = CountingWorld([(4.9, 4.0, 5.1, 6.0)])  # a post in the middle of the edges across it
    edge = bisected_edge(SPACE, world, 0.05)
    rng = np.random.default_rng(0)
    for _ in range(200):
        a, b = rng.uniform(1.0, 9.0, 2), rng.uniform(1.0, 9.0, 2)
        if not (world.config_free(a) and world.config_free(b)):
            continue
        qs = SPACE.discretize(a, b, 0.05)
        assert edge(a, b) == bool(np.all(world.configs_free(qs)))
    world.asked = 0
    a, b = np.array([1.0, 5.0]), np.array([9.0, 5.0])  # 161 configurations, the middle one colliding
    assert not edge(a, b) and world.asked == 1
    world.asked = 0
    a, b = np.array([1.0, 2.0]), np.array([9.0, 2.0])  # free: every configuration checked once
    assert edge(a, b) and world.asked == len(SPACE.discretize(a, b, 0.05))


def test_its_probes_and_the_rest_split_the_edge():
    world = CountingWorld([(4.9, 4.0, 5.1, 6.0)])
    edge = bisected_edge(SPACE, world, 0.05)
    for a, b in (([1.0, 2.0], [9.0, 2.0]), ([1.0, 2.0], [1.2, 2.0])):  # 161 configurations, then 5
        a, b = np.array(a), np.array(b)
        n = len(SPACE.discretize(a, b, 0.05))
        world.asked = 0
        assert edge(a, b, "probes")
        probed = world.asked
        assert probed == min(n, PROBES)
        assert edge(a, b, "rest") and world.asked == n
    a, b = np.array([0.5, 5.05]), np.array([8.5, 5.05])  # the post between the probes: only the rest sees it
    assert edge(a, b, "probes") and not edge(a, b, "rest") and not edge(a, b)
