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


# issue 32: the validate survivors of the mutation run (docs/reliability.md), each expectation worked by hand
WRAPPED = ConfigSpace(("x", "theta"), np.array([0.0, -np.pi]), np.array([10.0, np.pi]), wrap=np.array([False, True]))


class Recording(BoxWorld):
    """The toy world, keeping every configuration it was asked about."""

    def __init__(self, boxes):
        super().__init__(boxes)
        self.seen = []

    def configs_free(self, qs):
        self.seen.append(np.atleast_2d(qs).copy())
        return super().configs_free(qs)


def test_a_join_across_pi_is_checked_along_the_short_arc_inside_the_space():
    # theta from 3.0 to -3.0 the short way (through pi: 2 pi - 6 = 0.283 rad); the band theta in [-3.12, -3.08]
    # (unwrapped 3.163..3.203, wider than the 0.01 spacing) lies on it, the band around 0 only on the long way
    q = np.array([[5.0, 3.0], [5.0, -3.0]])
    on_arc = Recording([(0.0, -3.12, 10.0, -3.08)])
    assert first_colliding_join(WRAPPED, on_arc, q, 0.01) == 0
    seen = np.concatenate(on_arc.seen)
    assert seen[:, 1].min() >= -np.pi and seen[:, 1].max() <= np.pi  # the checker sees angles in the space's range
    assert first_colliding_join(WRAPPED, Recording([(0.0, -0.1, 10.0, 0.1)]), q, 0.01) is None


def test_a_two_sample_motion_through_a_wall_collides_on_its_only_join():
    q = np.array([[1.0, 5.0], [9.0, 5.0]])
    assert first_colliding_join(SPACE, BoxWorld([(4.95, 0.0, 5.05, 10.0)]), q, 0.01) == 0
    assert first_colliding_join(SPACE, BoxWorld([]), q, 0.01) is None
    assert first_colliding_join(SPACE, BoxWorld([]), q[:1], 0.01) is None  # one sample: no motion


def test_a_start_in_collision_counts_by_default():
    q = np.array([[1.0, 5.0], [2.0, 5.0], [3.0, 5.0]])
    world = BoxWorld([(0.5, 4.5, 1.5, 5.5)])  # around the start, left at x = 1.5
    assert first_colliding_join(SPACE, world, q, 0.1) == 0
    assert first_colliding_join(SPACE, world, q, 0.1, from_first_free=True) is None


def test_a_single_colliding_point_is_found():
    # x = 0, 0.25, 0.5, 0.75, 1 along one join: only x = 0.5 is inside the thin wall
    q = np.array([[0.0, 5.0], [1.0, 5.0]])
    assert first_colliding_join(SPACE, BoxWorld([(0.49, 0.0, 0.51, 10.0)]), q, 0.25) == 0


def test_dense_points_and_owners_worked_by_hand():
    # arc length 1 at 0.3: ceil(1 / 0.3) = 4 steps of 0.25; the point on sample 1 (x = 0.25) follows sample 1
    dense, owner = _dense(SPACE, np.array([[0.0, 0.0], [0.25, 0.0], [1.0, 0.0]]), 0.3)
    assert np.allclose(dense[:, 0], [0.0, 0.25, 0.5, 0.75, 1.0]) and np.all(dense[:, 1] == 0.0)
    assert owner.tolist() == [0, 1, 1, 1, 1]
    # shorter than the resolution: its two ends only
    dense, owner = _dense(SPACE, np.array([[0.0, 0.0], [0.2, 0.0]]), 0.3)
    assert np.allclose(dense, [[0.0, 0.0], [0.2, 0.0]]) and owner.tolist() == [0, 0]
    # a motion that does not move: its configuration twice, finite
    dense, owner = _dense(SPACE, np.array([[0.5, 0.5], [0.5, 0.5]]), 0.3)
    assert np.array_equal(dense, [[0.5, 0.5], [0.5, 0.5]]) and owner.tolist() == [0, 0]


class TrustingAlong(BoxWorld):
    """A checker whose sequence shortcut (``configs_free_along``) wrongly calls everything free."""

    def configs_free_along(self, qs):
        return np.ones(len(qs), bool)


def test_the_recheck_does_not_trust_the_timings_sequence_shortcut():
    # the re-check (trajectory_problems' path) asks configs_free; the timing's own check (along=True) the shortcut
    q = np.array([[1.0, 5.0], [9.0, 5.0]])
    world = TrustingAlong([(4.95, 0.0, 5.05, 10.0)])
    assert first_colliding_join(SPACE, world, q, 0.01) == 0
    assert first_colliding_join(SPACE, world, q, 0.01, along=True) is None
