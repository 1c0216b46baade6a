"""Shortcutting and the smooth curve on the 2-D toy world (no Drake)."""

import numpy as np
import pytest

from lazyground.motion.curve import blended_curve, unwrap_path
from lazyground.motion.validate import first_colliding_join
from lazyground.motion.edges import bisected_edge
from lazyground.motion.shortcut import (ShortcutSettings, ShortcutStatus, _FineCheck, _greedy, _Path, _remembered, _shorten,
                                        shortcut_path)
from lazyground.planning import PlannerSettings, path_is_valid, solve
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition
from tests.counts import PLANNER_BY_COUNTS
from tests.unit.toy import REACHABLE, SPACE, START, WALLS, BoxWorld, CountingWorld, goal_source

SETTINGS = PlannerSettings(step_size=0.5, goal_bias=0.1, **PLANNER_BY_COUNTS)
BUDGET = ShortcutSettings(max_iterations=200, time_budget=1e9)  # iterations decide, never the clock
FINE = SETTINGS.resolution / SETTINGS.validation_factor


def planned(seed):
    world = BoxWorld(WALLS)
    res = solve(SPACE, world, goal_source(world, [REACHABLE]), START, SETTINGS, np.random.default_rng(seed), seed=seed)
    assert res.solved
    return world, res.path


def shorten(world, path, seed, settings=BUDGET, keep_last=False):
    return shortcut_path(SPACE, world, path, SETTINGS.resolution, SETTINGS.validation_factor, settings,
                         np.random.default_rng(seed), keep_last_segment=keep_last)


@pytest.mark.parametrize("seed", range(6))
def test_shortcut_never_lengthens_stays_valid_and_keeps_the_ends(seed):
    world, path = planned(seed)
    out = shorten(world, path, seed)
    assert out.length <= out.raw_length + 1e-12
    assert np.array_equal(out.path[0], path[0]) and np.array_equal(out.path[-1], path[-1])
    assert path_is_valid(SPACE, world, out.path, FINE / 4) == -1  # finer still than the fine check
    assert np.isclose(out.length, SPACE.path_length(out.path))
    assert out.raw_length == pytest.approx(SPACE.path_length(path))


def test_shortcut_shortens_the_toy_paths_substantially():
    ratios = []
    for seed in range(6):
        world, path = planned(seed)
        ratios.append(shorten(world, path, seed).length / SPACE.path_length(path))
    # through the wall's gap: the direct route is ~13.5 long; RRT paths wander 1.2-2x that
    assert np.median(ratios) < 0.85


def test_shortcut_is_deterministic_in_the_seed():
    world, path = planned(0)
    a, b = shorten(world, path, 5), shorten(world, path, 5)
    assert np.array_equal(a.path, b.path) and a.iterations == b.iterations <= BUDGET.max_iterations


def test_disabled_keeps_the_raw_path():
    world, path = planned(1)
    out = shorten(world, path, 1, ShortcutSettings(enabled=False))
    assert out.status is ShortcutStatus.DISABLED and out.path is out.raw_path and out.length == out.raw_length


def test_the_final_approach_segment_is_kept():
    world, path = planned(2)
    out = shorten(world, path, 2, keep_last=True)
    assert np.array_equal(out.path[-2:], path[-2:])


def test_a_wall_thinner_than_the_planner_resolution_is_caught_by_the_fine_check():
    # The wall at x in [5, 5.01] hides between the planner's checks (every 0.05) along a shortcut
    # but not between the fine ones (every 0.005): the shortened path must go around it.
    thin = BoxWorld([(5.0, 0.0, 5.01, 8.0)])
    path = np.array([[1.0, 1.0], [3.0, 8.5], [7.0, 8.5], [9.0, 1.0]])
    assert path_is_valid(SPACE, thin, path, FINE) == -1
    assert thin.edge_free(np.array([1.0, 1.0]), np.array([9.0, 1.03]), SETTINGS.resolution)  # the coarse check misses it
    outs = [shorten(thin, path, seed) for seed in range(10)]
    for out in outs:
        assert path_is_valid(SPACE, thin, out.path, FINE / 4) == -1
    assert any(o.status is ShortcutStatus.BACKTRACKED for o in outs)
    # every seed's first, lazy greedy pass goes straight through the wall and fails the final fine check:
    # the shortening is redone with the greedy's fine checks and goes around (never the raw path)
    assert all(o.length < o.raw_length for o in outs)
    # the attempts of both runs together stay within max_iterations
    capped = ShortcutSettings(max_iterations=30, patience=1000, time_budget=1e9)
    assert all(shorten(thin, path, seed, capped).iterations == 30 for seed in range(3))


def test_the_lazy_greedy_pass_gives_the_checked_ones_path_with_fewer_checks():
    # Its segments are checked finely only if they are still in the final path; when none fails, the
    # path is the one the greedy pass checking each segment as it goes gives (the rest is the same). With
    # small moves allowed, the relaxation moves the greedy's corners on some seeds (2 and 4 here), and its
    # segments' fine checks were wasted.
    settings = ShortcutSettings(max_iterations=200, time_budget=1e9, min_gain=1e-4)
    saved = 0
    for seed in range(6):
        _, path = planned(seed)
        start = _Path(SPACE, list(path), [0] * (len(path) - 1))
        out, asked = {}, {}
        for lazy in (True, False):
            world = CountingWorld(WALLS)
            fine = _FineCheck(SPACE, world, FINE, path)
            edge = bisected_edge(SPACE, world, SETTINGS.resolution)
            versions, _, _ = _shorten(SPACE, edge, fine, start, settings, np.random.default_rng(seed), StopCondition(), lazy)
            out[lazy], asked[lazy] = np.array(versions[-1].q), world.asked
        assert np.array_equal(out[True], out[False])
        assert asked[True] <= asked[False]
        saved += asked[True] < asked[False]
    assert saved >= 2


def test_an_edge_is_checked_once_in_a_shortening():
    # a redone shortening's greedy pass asks the first run's edges again: the answers are kept
    world = CountingWorld(WALLS)
    edge = _remembered(bisected_edge(SPACE, world, SETTINGS.resolution))
    a, b = np.array([1.0, 1.0]), np.array([3.0, 6.0])
    first = edge(a, b)
    asked = world.asked
    assert edge(a.copy(), b.copy()) == first and world.asked == asked > 0

def test_blended_curve_runs_from_start_to_goal_near_the_corners():
    path = np.array([[1.0, 1.0], [3.0, 8.5], [6.0, 8.5], [8.0, 9.0]])
    for blend in (0.3, 0.1, 0.03):
        curve = blended_curve(path, blend)
        assert np.allclose(curve(0.0), path[0]) and np.allclose(curve(1.0), path[-1])
        q = curve(np.linspace(0.0, 1.0, 4000))
        # the curve stays within blend x the longest segment of the polyline
        seg = [np.min(np.linalg.norm(q[:, None] - np.linspace(a, b, 2000)[None], axis=2), axis=1) for a, b in zip(path[:-1], path[1:])]
        assert np.min(seg, axis=0).max() <= blend * 8.0


def test_the_join_check_finds_a_corner_cut_into_an_obstacle():
    # A box sits inside the corner at (5, 5): the polyline goes around it, a wide blend cuts into it.
    world = BoxWorld([(4.3, 4.3, 4.9, 4.9)])
    path = np.array([[1.0, 5.0], [5.0, 5.0], [5.0, 1.0]])
    assert path_is_valid(SPACE, world, path, 0.005) == -1
    u = np.linspace(0.0, 1.0, 500)
    assert first_colliding_join(SPACE, world, blended_curve(path, 0.3)(u), 0.005) is not None
    assert first_colliding_join(SPACE, world, blended_curve(path, 0.03)(u), 0.005) is None
    assert first_colliding_join(SPACE, world, path, 0.005) is None


def test_unwrap_takes_the_short_way_round():
    space = ConfigSpace(("x", "theta"), np.array([0.0, -np.pi]), np.array([10.0, np.pi]), wrap=np.array([False, True]))
    path = np.array([[0.0, 3.0], [1.0, -3.0], [2.0, -2.0]])
    out = unwrap_path(space, path)
    assert np.allclose(out[:, 1], [3.0, 2 * np.pi - 3.0, 2 * np.pi - 2.0])


class _Graze:
    """Free everywhere but a square of half-width h around x: an obstacle narrower than the fine resolution."""

    def __init__(self, x, h=2e-4):
        self.x, self.h = np.asarray(x, float), h

    def configs_free(self, qs):
        return ~np.all(np.abs(np.atleast_2d(qs) - self.x) <= self.h, axis=1)


def test_a_merged_run_of_the_input_path_is_checked_again_at_its_own_points():
    # The input path's segments passed the planner's fine check; one segment over a collinear run of them
    # (or a piece of one) is checked at other points, and a graze between the two sets of points must not
    # slip through (corpus big_box_table, seed 0, before the fix).
    from lazyground.motion.shortcut import _FineCheck, _Path

    a, b, c = np.array([1.0, 1.0]), np.array([2.0, 1.0]), np.array([3.013, 1.0])
    raw = np.array([a, b, c])
    merged = SPACE.discretize(a, c, FINE)
    own = np.vstack([SPACE.discretize(a, b, FINE), SPACE.discretize(b, c, FINE)])
    gaps = np.min(np.abs(merged[:, None, 0] - own[None, :, 0]), axis=1)
    x = merged[np.argmax(gaps)]  # a point of the merged segment's check, far from every point of the input's
    world = _Graze(x, h=min(2e-4, 0.5 * gaps.max()))
    assert path_is_valid(SPACE, world, raw, FINE) == -1  # the input path passes its own check
    assert path_is_valid(SPACE, world, np.array([a, c]), FINE) == 0  # the merged segment does not
    fine = _FineCheck(SPACE, world, FINE, raw)
    assert fine.first_failure(_Path(SPACE, [a, c], [0])) == 0  # traced to the input path: shortcut returns it
    assert fine.first_failure(_Path(SPACE, [a, b, c], [0, 0])) is None


def test_the_greedy_search_on_probes_keeps_only_points_whose_whole_edge_passes():
    # probes that pass everything (they miss every obstacle): the points the search settles on are checked in
    # full ("rest"); here only points at x <= 1 are seen whole, and the greedy's segments are exactly those
    q = [np.array([0.0, 0.0]), np.array([0.0, 4.0]), np.array([4.0, 4.0])]
    asked = []

    def edge(a, b, part="all"):
        asked.append(part)
        return bool(b[0] <= 1.0 + 1e-12)

    out = _greedy(SPACE, edge, None, _Path(SPACE, q, [0, 0]), born=1, probe=lambda a, b: True)
    assert all(edge(a, b) for a, b in zip(out.q[:-2], out.q[1:-1]))  # the last is a piece of the input's own segment
    assert 0.9 < out.q[1][0] <= 1.0 and out.q[1][1] == 4.0  # the farthest point seen whole, within 4 / 2**6
    assert "rest" in asked


def test_the_fine_check_stops_at_the_first_failing_segment():
    # a version whose second segment crosses the wall: its third segment is not checked (the version goes);
    # an earlier version that keeps that segment checks it then
    world = CountingWorld(WALLS)
    a, b, c, d = np.array([1.0, 1.0]), np.array([3.0, 1.0]), np.array([6.0, 1.0]), np.array([6.0, 0.2])
    fine = _FineCheck(SPACE, world, FINE, np.array([a, d]))
    assert fine.first_failure(_Path(SPACE, [a, b, c, d], [2, 3, 1])) == 3
    first_two = len(SPACE.discretize(a, b, FINE)) + len(SPACE.discretize(b, c, FINE))
    assert world.asked <= first_two  # c -> d was not asked about
    assert fine.first_failure(_Path(SPACE, [a, c, d], [0, 1])) == 0 and world.asked <= first_two + len(SPACE.discretize(a, c, FINE))
    assert fine.first_failure(_Path(SPACE, [c, d], [1])) is None
