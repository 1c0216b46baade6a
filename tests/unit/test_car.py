"""Car kinematics (issue #17): Reeds-Shepp / Dubins curves and the car configuration space.

Self-contained checks (analytic cases, symmetry, triangle inequality, every word ends at
its goal, steering consistency, curve sampling) and, when OMPL is installed, lengths
against OMPL's ReedsSheppStateSpace / DubinsStateSpace on 1,000 random pairs.
"""

import math

import numpy as np
import pytest

from lazyground.planning import curves
from lazyground.planning.car import CarSpace, gear_changes
from lazyground.planning.kinematics import make_space
from lazyground.planning.space import ConfigSpace

R = 3.86  # the bundled car's turning radius
OFFSET = -1.35  # its rear axle behind the body frame
BASE = ConfigSpace(("x", "y", "th"), np.array([0.0, 0.0, -np.pi]), np.array([40.0, 30.0, np.pi]), None,
                   np.array([False, False, True]))
SOLVERS = {"reeds-shepp": curves.reeds_shepp_word, "dubins": curves.dubins_word}


def _pairs(n, seed=0, span=10.0):
    rng = np.random.default_rng(seed)
    lo, hi = [-span, -span, -math.pi], [span, span, math.pi]
    return list(zip(rng.uniform(lo, hi, (n, 3)), rng.uniform(lo, hi, (n, 3))))


def _end_of(word):
    x = y = th = 0.0
    for kind, s in word:
        x, y, th = curves.advance(x, y, th, kind, s)
    return x, y, th


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_every_word_ends_at_its_goal(kinematics):
    for a, b in _pairs(500):
        rel = curves.relative(a, b, 1.0)
        x, y, th = _end_of(SOLVERS[kinematics](*rel))
        assert abs(x - rel[0]) < 1e-6 and abs(y - rel[1]) < 1e-6 and abs(curves.mod2pi(th - rel[2])) < 1e-6


def test_analytic_cases():
    rs = lambda *q: curves.word_length(curves.reeds_shepp_word(*q))  # noqa: E731
    db = lambda *q: curves.word_length(curves.dubins_word(*q))  # noqa: E731
    assert rs(3.0, 0.0, 0.0) == pytest.approx(3.0)  # straight ahead
    assert rs(-3.0, 0.0, 0.0) == pytest.approx(3.0)  # straight back: reverse gear
    assert db(-3.0, 0.0, 0.0) > 3.0 + 2 * math.pi - 1e-9  # Dubins must turn round
    assert rs(1.0, 1.0, math.pi / 2) == pytest.approx(math.pi / 2)  # a quarter circle left
    assert rs(1.0, -1.0, -math.pi / 2) == pytest.approx(math.pi / 2)  # ... and right
    assert db(1.0, 1.0, math.pi / 2) == pytest.approx(math.pi / 2)
    assert rs(0.0, 0.0, 0.0) == pytest.approx(0.0)


def test_reeds_shepp_metric_properties():
    space = make_space(BASE, "reeds-shepp", R, OFFSET)
    rng = np.random.default_rng(1)
    for _ in range(300):
        a, b, c = (space.sample(rng) for _ in range(3))
        d_ab = space.distance(a, b)
        assert d_ab == pytest.approx(space.distance(b, a), rel=1e-9, abs=1e-9)  # reversing the drive is allowed
        assert d_ab <= space.distance(a, c) + space.distance(c, b) + 1e-9
        # no shorter than the straight line between the reference points, nor than the turn it makes
        pa, pb = space.reference(a), space.reference(b)
        assert d_ab >= math.hypot(*(pb[:2] - pa[:2])) - 1e-9
        assert d_ab >= R * abs(curves.mod2pi(b[2] - a[2])) - 1e-9


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_dubins_never_shorter_and_forwards_only(kinematics):
    rs = make_space(BASE, "reeds-shepp", R)
    space = make_space(BASE, kinematics, R)
    for a, b in _pairs(200, seed=2):
        assert space.distance(a, b) >= rs.distance(a, b) - 1e-9
        if kinematics == "dubins":
            assert all(s >= 0.0 for _, s in space.word(a, b))


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_steer_moves_step_along_the_shortest_curve(kinematics):
    space = make_space(BASE, kinematics, R, OFFSET)
    rng = np.random.default_rng(3)
    for _ in range(200):
        a, b = space.sample(rng), space.sample(rng)
        step = rng.uniform(0.2, 4.0)
        q, reached = space.steer(a, b, step)
        d = space.distance(a, b)
        assert reached == (d <= step)
        if not reached:
            fresh = make_space(BASE, kinematics, R, OFFSET)  # no cached curve: solved from scratch
            assert fresh.distance(a, q) == pytest.approx(step, rel=1e-7)
            assert fresh.distance(a, q) + fresh.distance(q, b) == pytest.approx(d, rel=1e-7)


def _assert_drivable(space: CarSpace, dense: np.ndarray, spacing: float):
    """Every step: origin within ``spacing``, reference point moving along its heading, curvature <= 1/r."""
    steps = np.diff(dense, axis=0)
    assert np.all(np.hypot(steps[:, 0], steps[:, 1]) <= spacing + 1e-9)
    ref = space.reference(dense)
    d = np.diff(ref[:, :2], axis=0)
    chord = np.hypot(d[:, 0], d[:, 1])
    turn = curves_wrap(np.diff(ref[:, 2]))
    moving = chord > 1e-9
    mid = ref[:-1, 2] + 0.5 * turn
    # the chord of an arc points along the heading halfway through it: parallel (forwards or reverse)
    cross = d[:, 0] * np.sin(mid) - d[:, 1] * np.cos(mid)
    assert np.all(np.abs(cross[moving]) <= 1e-9 + 1e-6 * chord[moving])
    assert np.all(np.abs(turn[moving]) <= chord[moving] / space.radius * (1 + 1e-3) + 1e-9)
    assert np.all(np.abs(turn[~moving]) <= 1e-9)  # no turning on the spot


def curves_wrap(a):
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_discretized_curves_are_drivable(kinematics):
    space = make_space(BASE, kinematics, R, OFFSET)
    rng = np.random.default_rng(4)
    for _ in range(100):
        a, b = space.sample(rng), space.sample(rng)
        dense = space.discretize(a, b, 0.1)
        assert np.allclose(dense[0], a) and np.array_equal(dense[-1], b)
        _assert_drivable(space, dense, 0.1)
        cusps = sum(1 for (_, s), (_, t) in zip(space.word(a, b)[:-1], space.word(a, b)[1:]) if s * t < 0)
        assert gear_changes(space.reference(dense)) == cusps
        assert space.interpolate(a, b, 0.0) == pytest.approx(a) and space.interpolate(a, b, 1.0) == pytest.approx(b)


def test_densify_keeps_waypoints_and_spacing():
    space = make_space(BASE, "reeds-shepp", R, OFFSET)
    rng = np.random.default_rng(5)
    path = np.array([space.sample(rng) for _ in range(4)])
    dense = space.dense_path(path)
    for q in path:
        assert np.min(np.abs(dense - q).sum(axis=1)) < 1e-9
    _assert_drivable(space, dense, 0.1)
    assert space.path_length(path) == pytest.approx(sum(space.distance(a, b) for a, b in zip(path[:-1], path[1:])))


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_a_fine_check_takes_the_samples_of_the_dense_paths_re_check(kinematics):
    """The planner fine-checks a curve a -> b; a test re-checks the dense path it returns, piece by piece, at the
    same resolution: both must test the same configurations, or a sliver of obstacle between one set lies on
    the other (stress run 7 of tools/stress.py: a 3.7 mm graze of a wall on parking_2 that one set missed)."""
    space = make_space(BASE, kinematics, R, OFFSET)
    rng = np.random.default_rng(6)
    for _ in range(50):
        a, b = space.sample(rng), space.sample(rng)
        fine = space.discretize(a, b, 0.01)
        dense = space.dense_path(np.array([a, b]))
        again = np.vstack([space.discretize(p, q, 0.01, skip_first=k > 0)
                           for k, (p, q) in enumerate(zip(dense[:-1], dense[1:]))])
        assert again.shape == fine.shape
        assert np.abs(again - fine).max() < 1e-6


class _WallChecker:
    """Free where x < wall; counts calls so the test sees which edge check ran."""

    def __init__(self, wall):
        self.wall, self.edge_calls = wall, 0

    def configs_free(self, qs):
        return np.asarray(qs)[:, 0] < self.wall

    def edge_free(self, a, b, resolution):
        self.edge_calls += 1
        return bool(np.all(self.configs_free(BASE.discretize(a, b, resolution))))

    def edge_fraction(self, a, b, resolution):
        self.edge_calls += 1
        return 1.0


def test_curve_edges_are_checked_along_the_curve():
    space = make_space(BASE, "reeds-shepp", R)
    checker = _WallChecker(wall=11.0)
    a, b = np.array([10.0, 5.0, 0.0]), np.array([10.0, 10.0, 0.0])  # a sideways shift: the curve swings past x = 11
    assert BASE.discretize(a, b, 0.05)[:, 0].max() < 11.0  # the straight line never does
    assert space.discretize(a, b, 0.05)[:, 0].max() > 11.0
    motion = space.motion_validator(checker)
    assert not motion.edge_free(a, b, 0.05)
    t = motion.edge_fraction(a, b, 0.05)
    assert 0.0 < t < 1.0
    q = space.interpolate(a, b, t)
    assert q[0] < 11.0  # the free prefix ends before the wall
    assert np.all(checker.configs_free(space.discretize(a, q, 0.01)))
    assert checker.edge_calls == 0  # the checker's linear edge check was never used
    assert BASE.motion_validator(checker).edge_free(a, b, 0.05) and checker.edge_calls == 1  # straight spaces still use it


def test_car_space_rejects_bad_input():
    with pytest.raises(ValueError):
        make_space(BASE, "teleport", R)
    with pytest.raises(ValueError):
        make_space(BASE, "reeds-shepp", 0.0)
    arm = ConfigSpace(("a", "b"), np.zeros(2), np.ones(2))
    with pytest.raises(ValueError):
        make_space(arm, "reeds-shepp", R)
    assert make_space(BASE, "holonomic", R) is BASE


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_lengths_match_ompl(kinematics):
    ob = pytest.importorskip("ompl.base")
    space = (ob.ReedsSheppStateSpace if kinematics == "reeds-shepp" else ob.DubinsStateSpace)(R)

    def state(q):
        s = space.allocState()
        s.setX(float(q[0])), s.setY(float(q[1])), s.setYaw(float(q[2]))
        return s

    ours = make_space(BASE, kinematics, R)
    worst = max(abs(ours.distance(a, b) - space.distance(state(a), state(b))) / space.distance(state(a), state(b))
                for a, b in _pairs(1000, seed=6))
    assert worst < 1e-6


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_planned_car_paths_are_drivable(kinematics):
    from lazyground.goals import ConfigGoalSource
    from lazyground.planning import solve
    from lazyground.planning.problem import PlannerSettings
    from lazyground.regions import ConfigRegion
    from tests.unit.toy import BoxWorld  # checks x and y only: a point car

    space = make_space(BASE, kinematics, R, OFFSET)
    world = BoxWorld([(18.0, 0.0, 20.0, 22.0)])  # a wall with a gap at the top
    goal = ConfigRegion(id="bay", interpretation="park:bay", object="bay",
                        lower=(30.0, 5.0, -0.15), upper=(30.5, 5.5, 0.15), wrap=(2,))
    settings = PlannerSettings(step_size=2.0, edge_resolution=0.1, time_limit=1e6, max_iterations=20_000,
                               goal_bias=0.1, goal_extension="connect", kinematics=kinematics)
    solved = 0
    for seed in range(3):
        res = solve(space, world, ConfigGoalSource((goal,), space, world), np.array([5.0, 5.0, 0.0]), settings,
                    np.random.default_rng(seed), seed=seed)
        if not res.solved:
            continue
        solved += 1
        assert goal.contains(res.path[-1])
        _assert_drivable(space, res.path, 0.1)
        assert np.all(world.configs_free(res.path))
        if kinematics == "dubins":  # (the gear changes are the motion's: lazyground.motion.car_shortcut)
            assert gear_changes(space.reference(res.path)) == 0
    assert solved == 3


@pytest.mark.parametrize("kinematics", sorted(SOLVERS))
def test_closest_is_the_shortest_curve_among_candidates(kinematics):
    """The bound-pruned ranking returns the node with the shortest curve to q (its length, ties aside)."""
    space = make_space(BASE, kinematics, R, OFFSET)
    rng = np.random.default_rng(7)
    for _ in range(200):
        q = space.sample(rng)
        nodes = [q + rng.normal(0.0, [3.0, 3.0, 1.0]) for _ in range(int(rng.integers(1, 16)))]
        lengths = [make_space(BASE, kinematics, R, OFFSET).distance(a, q) for a in nodes]
        assert lengths[space.closest(nodes, q)] == pytest.approx(min(lengths), rel=1e-9, abs=1e-9)


def test_tree_nearest_ranks_a_cars_candidates_by_driving_distance():
    """Beside the car, facing it, is near in the embedding but far to drive; a node behind it is not."""
    from lazyground.planning.tree import Tree

    space = make_space(BASE, "reeds-shepp", R, 0.0)
    q = np.array([20.0, 15.0, 0.0])
    aside = np.array([20.0, 16.0, 0.0])  # 1 m to the left, same heading: an S-manoeuvre
    behind = np.array([18.5, 15.0, 0.0])  # 1.5 m straight back
    tree = Tree(space)
    tree.add_root(aside)
    tree.add(behind, 0)
    assert space.distance(aside, q) > space.distance(behind, q) == pytest.approx(1.5)
    assert np.linalg.norm(space.embed(aside) - space.embed(q)) < np.linalg.norm(space.embed(behind) - space.embed(q))
    assert tree.nearest(q) == 1
    assert Tree(BASE).nearest(q) == -1  # an empty tree has none
