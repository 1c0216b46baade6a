"""Vertex relaxation (lazyground.motion.relax) alone and inside the shortcutting, on the 2-D toy world (no Drake)."""

from dataclasses import replace

import numpy as np
import pytest

from lazyground.motion.relax import relax_sweep, subdivide, toward_segment
from lazyground.motion.shortcut import ShortcutSettings, ShortcutStatus, shortcut_path
from lazyground.planning import PlannerSettings, path_is_valid
from tests.counts import PLANNER_BY_COUNTS
from tests.unit.toy import SPACE, WALLS, BoxWorld

SETTINGS = PlannerSettings(step_size=0.5, goal_bias=0.1, **PLANNER_BY_COUNTS)
FINE = SETTINGS.resolution / SETTINGS.validation_factor
RELAX_ONLY = ShortcutSettings(greedy=False, max_iterations=0, time_budget=1e9, relax_pieces=16, relax_sweeps=10,
                              min_gain=1e-3)  # no clock, no shortcut; moves down to 0.1 % of the length
# through the wall's gap at y in [8, 9], with detours on both sides
BENT = np.array([[1.0, 1.0], [1.5, 6.0], [3.0, 9.5], [4.5, 8.5], [6.0, 9.5], [6.0, 5.0], [8.0, 4.5], [8.0, 5.5]])


def shorten(world, path, settings, seed=0):
    return shortcut_path(SPACE, world, path, SETTINGS.resolution, SETTINGS.validation_factor, settings,
                         np.random.default_rng(seed))


def test_the_step_goes_to_the_nearest_point_of_the_neighbours_segment():
    a, b = np.array([0.0, 0.0]), np.array([2.0, 0.0])
    assert np.allclose(toward_segment(SPACE, a, np.array([1.0, 1.0]), b), [0.0, -1.0])
    assert np.allclose(toward_segment(SPACE, a, np.array([3.0, 1.0]), b), [-1.0, -1.0])  # beyond b: to b itself


def test_a_blocked_move_is_tried_at_half_its_step_and_never_lengthens():
    q = [np.array([1.0, 1.0]), np.array([2.0, 2.0]), np.array([3.0, 1.0])]
    open_world, box = BoxWorld([]), BoxWorld([(1.9, 0.9, 2.1, 1.2)])  # the box blocks the full step, not the half one
    edge = lambda world: lambda a, b: world.edge_free(a, b, SETTINGS.resolution)  # noqa: E731
    moved, new, n = relax_sweep(SPACE, edge(open_world), q, [0, 0], 7, halvings=1, min_gain=1e-9)
    assert n == 1 and np.allclose(moved[1], [2.0, 1.0]) and new == [7, 7]
    moved, _, n = relax_sweep(SPACE, edge(box), q, [0, 0], 7, halvings=1, min_gain=1e-9)
    assert n == 1 and np.allclose(moved[1], [2.0, 1.5])
    stuck, new, n = relax_sweep(SPACE, edge(box), q, [0, 0], 7, halvings=0, min_gain=1e-9)
    assert n == 0 and np.array_equal(stuck[1], q[1]) and new == [0, 0]
    assert SPACE.path_length(np.array(moved)) < SPACE.path_length(np.array(q))


def test_subdividing_keeps_the_path_and_each_segments_flag():
    q, new = subdivide(SPACE, [np.array([0.0, 0.0]), np.array([4.0, 0.0]), np.array([4.0, 1.0])], [0, 3], 5)
    assert len(q) == 6 and new == [0, 0, 0, 0, 3]
    assert np.isclose(SPACE.path_length(np.array(q)), 5.0) and np.array_equal(q[-1], [4.0, 1.0])


def test_relaxation_alone_pulls_a_bent_path_tight_and_it_passes_the_fine_check():
    world = BoxWorld(WALLS)
    assert path_is_valid(SPACE, world, BENT, FINE) == -1
    out = shorten(world, BENT, RELAX_ONLY)
    assert out.status is ShortcutStatus.SHORTENED and out.accepted >= 2  # sweeps that moved
    assert out.length < 0.8 * out.raw_length  # 20.0 -> 14.8
    assert path_is_valid(SPACE, world, out.path, FINE) == -1
    assert np.array_equal(out.path[0], BENT[0]) and np.array_equal(out.path[-1], BENT[-1])
    off = shorten(world, BENT, ShortcutSettings(greedy=False, max_iterations=0, relax_pieces=0))
    assert off.status is ShortcutStatus.UNCHANGED


def test_relaxation_keeps_the_final_approach_segment():
    world = BoxWorld(WALLS)
    out = shortcut_path(SPACE, world, BENT, SETTINGS.resolution, SETTINGS.validation_factor, RELAX_ONLY,
                        np.random.default_rng(0), keep_last_segment=True)
    assert np.array_equal(out.path[-2:], BENT[-2:]) and out.length < 0.9 * out.raw_length  # 20.0 -> 16.1


def test_a_relaxed_segment_through_a_wall_thinner_than_the_planner_resolution_is_backtracked():
    # The thin wall hides between the planner's checks along the relaxed segments, not between the fine ones.
    thin = BoxWorld([(5.0, 0.0, 5.01, 8.0)])
    path = np.array([[2.0, 1.5], [5.0, 9.0], [8.0, 1.0]])
    assert path_is_valid(SPACE, thin, path, FINE) == -1
    out = shorten(thin, path, RELAX_ONLY)
    assert out.status is ShortcutStatus.BACKTRACKED and out.length < out.raw_length
    assert path_is_valid(SPACE, thin, out.path, FINE / 4) == -1


@pytest.mark.parametrize("seed", [0, 4])
def test_shortcutting_with_relaxation_is_reproducible_in_the_seed(seed):
    world = BoxWorld(WALLS)
    settings = ShortcutSettings(time_budget=1e9)
    a, b = shorten(world, BENT, settings, seed), shorten(world, BENT, settings, seed)
    assert np.array_equal(a.path, b.path) and a.iterations == b.iterations
    without = shorten(world, BENT, ShortcutSettings(time_budget=1e9, relax_pieces=0), seed)
    assert not np.array_equal(a.path, without.path)  # the relaxation did move waypoints


def test_negative_relaxation_settings_are_refused():
    with pytest.raises(ValueError, match="relax_pieces"):
        ShortcutSettings(relax_sweeps=-1)


def test_a_second_greedy_pass_after_the_relaxation_drops_waypoints_and_keeps_the_fine_check():
    world, thin = BoxWorld(WALLS), BoxWorld([(5.0, 0.0, 5.01, 8.0)])
    once = shorten(world, BENT, RELAX_ONLY)
    twice = shorten(world, BENT, replace(RELAX_ONLY, regreedy=True))
    assert len(twice.path) < len(once.path) and twice.length <= once.length
    assert path_is_valid(SPACE, world, twice.path, FINE) == -1
    # pieces of relaxed segments keep their flags through the second pass: the thin wall is still caught
    out = shorten(thin, np.array([[2.0, 1.5], [5.0, 9.0], [8.0, 1.0]]), replace(RELAX_ONLY, regreedy=True))
    assert path_is_valid(SPACE, thin, out.path, FINE / 4) == -1
