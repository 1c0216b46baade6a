"""What the motion's collision checks may skip, and why it is safe (no Drake).

The timing checks only the curve off the path (the rounded corners) when the path is known
free at the fine resolution: these tests pin down that the curve's other spans are pieces of
the path's segments, and that the join check skips exactly the joins it is told are free.
"""

import numpy as np
import pytest

from lazyground.motion.curve import blended_curve, on_segment_spans
from lazyground.motion.shortcut import ShortcutSettings, shortcut_path
from lazyground.motion.validate import _dense, first_colliding_join
from lazyground.planning import PlannerSettings, path_is_valid, solve
from lazyground.planning.space import ConfigSpace
from tests.unit.toy import REACHABLE, SPACE, START, WALLS, BoxWorld, goal_source

SETTINGS = PlannerSettings(step_size=0.5, time_limit=30.0, goal_bias=0.1)
FINE = SETTINGS.resolution / SETTINGS.validation_factor


def distance_to_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    d = b - a
    t = np.clip((p - a) @ d / (d @ d), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * d), axis=1)


@pytest.mark.parametrize("blend", [0.3, 0.2, 0.07, 0.02])
def test_the_curve_runs_on_the_segments_away_from_the_corners(blend):
    path = np.random.default_rng(7).normal(size=(6, 3)) * 2.0
    curve = blended_curve(path, blend)
    spans = on_segment_spans(np.arange(len(path)))
    assert spans == (0, 3, 6, 9, 12)  # one per segment
    b = curve.breaks
    for j in range(len(b) - 1):
        q = curve(np.linspace(b[j], b[j + 1], 200))
        off = min(distance_to_segment(q, a, c).max() for a, c in zip(path[:-1], path[1:]))
        if j in spans:  # on its own segment, exactly
            assert distance_to_segment(q, path[j // 3], path[j // 3 + 1]).max() < 1e-9
        else:  # a rounded corner leaves every segment
            assert off > 1e-3


def test_a_segment_over_a_dropped_waypoint_is_not_on_the_path():
    # waypoints 0, 1, 3, 4 kept: segment 1 -> 3 of the curve's polyline is no segment of the path
    assert on_segment_spans(np.array([0, 1, 3, 4])) == (0, 6)


def test_the_dense_join_points_are_the_discretized_joins():
    space = ConfigSpace(("x", "theta"), np.array([0.0, -np.pi]), np.array([10.0, np.pi]), wrap=np.array([False, True]))
    q = np.cumsum(np.random.default_rng(0).normal(0.0, 0.02, (300, 2)), axis=0) + [5.0, 3.0]
    for resolution in (0.005, 0.03):
        dense, owner = _dense(space, q, resolution)
        # the reference: one discretize per join, the joins thinned to one per resolution of arc length
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(space.embed(q), axis=0), axis=1))])
        keep = np.unique(np.concatenate([np.searchsorted(s, np.arange(0.0, s[-1], resolution), side="right") - 1, [0, len(q) - 1]]))
        ref = np.vstack([space.discretize(q[a], q[b], resolution, skip_first=k > 0) for k, (a, b) in enumerate(zip(keep[:-1], keep[1:]))])
        assert np.abs(space.difference(ref, space.interpolate(dense, dense, 0.0))).max() < 1e-12
        assert np.all(np.diff(owner) >= 0) and owner[0] == 0 and owner[-1] == keep[-2]


def test_joins_known_free_are_not_checked_and_the_others_are():
    world = BoxWorld([(4.95, 0.0, 5.05, 10.0)])  # a wall across x = 5
    q = np.column_stack([np.linspace(1.0, 9.0, 81), np.full(81, 5.0)])  # joins 39 and 40 cross it
    assert first_colliding_join(SPACE, world, q, FINE) == 39
    known = np.zeros(80, bool)
    known[:39] = True
    before = world.checks
    assert first_colliding_join(SPACE, world, q, FINE, known_free=known) == 39
    skipped = world.checks - before
    known[39:41] = True  # (a wrong claim, to show the crossing joins are then not checked)
    assert first_colliding_join(SPACE, world, q, FINE, known_free=known) is None
    assert skipped < 0.6 * len(_dense(SPACE, q, FINE)[0])
    assert first_colliding_join(SPACE, world, q, FINE, known_free=np.ones(80, bool)) is None


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
                            ShortcutSettings(max_iterations=0), np.random.default_rng(seed))
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
