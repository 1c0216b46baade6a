"""The motion's own checks and shortcut passes on the toy world (no Drake): the dense join
points, the join check, the greedy pass and the no-progress stop."""

import numpy as np

from lazyground.motion.shortcut import ShortcutSettings, shortcut_path
from lazyground.motion.validate import _dense, first_colliding_join
from lazyground.planning import PlannerSettings, path_is_valid, solve
from lazyground.planning.space import ConfigSpace
from tests.counts import PLANNER_BY_COUNTS
from tests.unit.toy import REACHABLE, SPACE, START, WALLS, BoxWorld, goal_source

SETTINGS = PlannerSettings(step_size=0.5, goal_bias=0.1, **PLANNER_BY_COUNTS)
FINE = SETTINGS.resolution / SETTINGS.validation_factor


def test_the_dense_join_points_follow_every_join_at_most_a_resolution_apart():
    space = ConfigSpace(("x", "theta"), np.array([0.0, -np.pi]), np.array([10.0, np.pi]), wrap=np.array([False, True]))
    q = np.cumsum(np.random.default_rng(0).normal(0.0, 0.02, (300, 2)), axis=0) + [5.0, 3.0]
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(space.embed(q), axis=0), axis=1))])
    for resolution in (0.005, 0.03):
        dense, owner = _dense(space, q, resolution)
        assert np.array_equal(dense[0], q[0]) and np.array_equal(dense[-1], q[-1])
        assert np.all(np.diff(owner) >= 0) and owner[0] == 0 and owner[-1] == len(q) - 2
        # every point lies on the join of its owner, at arc length t along the polyline
        a, b = q[owner], q[owner + 1]
        d = space.difference(a, b)
        frac = np.einsum("ij,ij->i", dense - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
        assert np.abs(a + frac[:, None] * d - dense).max() < 1e-12 and frac.min() > -1e-9 and frac.max() < 1 + 1e-9
        t = s[owner] + frac * (s[owner + 1] - s[owner])
        steps = np.diff(t)
        assert steps.min() > 0 and steps.max() <= resolution * (1 + 1e-9)
        # as few as that spacing needs (discretizing join by join checked up to twice as many)
        assert len(dense) == int(np.ceil(s[-1] / resolution)) + 1


def test_the_join_check_finds_the_first_crossing_join():
    world = BoxWorld([(4.95, 0.0, 5.05, 10.0)])  # a wall across x = 5
    q = np.column_stack([np.linspace(1.0, 9.0, 81), np.full(81, 5.0)])  # joins 39 and 40 cross it
    assert first_colliding_join(SPACE, world, q, FINE) == 39
    assert first_colliding_join(SPACE, world, q[:39], FINE) is None


def planned(seed):
    world = BoxWorld(WALLS)
    res = solve(SPACE, world, goal_source(world, [REACHABLE]), START, SETTINGS, np.random.default_rng(seed), seed=seed)
    assert res.solved
    return world, res.path


def test_the_greedy_pass_alone_shortens_and_its_segments_pass_the_fine_check():
    ratios = []
    for seed in range(6):
        world, path = planned(seed)
        out = shortcut_path(SPACE, world, path, SETTINGS.resolution, SETTINGS.validation_factor,
                            ShortcutSettings(max_iterations=0, relax_pieces=0), np.random.default_rng(seed))
        assert out.iterations == 0
        assert path_is_valid(SPACE, world, out.path, FINE / 4) == -1
        assert np.array_equal(out.path[0], path[0]) and np.array_equal(out.path[-1], path[-1])
        ratios.append(out.length / out.raw_length)
    assert max(ratios) <= 1.0 and np.median(ratios) < 0.85


def test_random_shortcuts_stop_when_they_stop_gaining():
    world, path = planned(3)
    out = shortcut_path(SPACE, world, path, SETTINGS.resolution, SETTINGS.validation_factor,
                        ShortcutSettings(max_iterations=10_000, time_budget=1e9, patience=5), np.random.default_rng(3))
    assert 5 <= out.iterations < 10_000
