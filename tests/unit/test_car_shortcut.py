"""Shortening a car's path along its own curves (lazyground.motion.car_shortcut, issue #17)."""

import numpy as np
import pytest

from lazyground.motion.car_shortcut import driven_lengths, shorten_car_path
from lazyground.planning.car import gear_changes
from lazyground.planning.kinematics import make_space
from lazyground.planning.search import path_is_valid
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition
from tests.unit.test_car import BASE, OFFSET, R, _assert_drivable
from tests.unit.toy import BoxWorld

NO_CLOCK = StopCondition()  # tests stop on attempts, never on the clock


def _planned(space, world, seed):
    from lazyground.goals import ConfigGoalSource
    from lazyground.planning import solve
    from lazyground.planning.problem import PlannerSettings
    from lazyground.regions import ConfigRegion

    goal = ConfigRegion(id="bay", interpretation="park:bay", object="bay",
                        lower=(30.0, 5.0, -0.15), upper=(30.5, 5.5, 0.15), wrap=(2,))
    settings = PlannerSettings(step_size=2.0, edge_resolution=0.1, time_limit=1e6, max_iterations=20_000,
                               goal_bias=0.05, goal_extension="extend", kinematics="reeds-shepp")
    res = solve(space, world, ConfigGoalSource((goal,), space, world), np.array([5.0, 5.0, 0.0]), settings,
                np.random.default_rng(seed), seed=seed)
    assert res.solved
    return res


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_shortened_car_paths_are_drivable_free_shorter_and_straighter(seed):
    space = make_space(BASE, "reeds-shepp", R, OFFSET)
    world = BoxWorld([(18.0, 0.0, 20.0, 22.0)])  # a wall with a gap at the top
    res = _planned(space, world, seed)
    cut = shorten_car_path(space, world, res.path, 0.1, 10.0, 200, NO_CLOCK, np.random.default_rng(seed))
    assert cut.raw_length == pytest.approx(res.path_length, rel=1e-6)  # driven length of the dense samples
    assert cut.raw_cusps == gear_changes(space.reference(res.path))
    assert np.array_equal(cut.path[0], res.path[0]) and np.array_equal(cut.path[-1], res.path[-1])
    _assert_drivable(space, cut.path, 0.1)
    # the independent re-check: every curve between consecutive samples, finer than the planner's
    assert path_is_valid(space, world, cut.path, 0.01) == -1
    assert cut.length == pytest.approx(driven_lengths(space, cut.path).sum(), rel=1e-6)
    assert cut.length < cut.raw_length and cut.cusps <= cut.raw_cusps
    assert cut.cusps == gear_changes(space.reference(cut.path))
    assert cut.accepted > 0 and cut.iterations == 200


def test_a_curve_that_fails_the_fine_recheck_is_put_back():
    """A wall thinner than the edge resolution: straight shortcuts through it pass the coarse check only."""
    space = make_space(ConfigSpace(("x", "y", "th"), np.array([-5.0, -5.0, -np.pi]), np.array([15.0, 15.0, np.pi]),
                                   None, np.array([False, False, True])), "reeds-shepp", 1.0)
    wall = BoxWorld([(4.994, -1.0, 5.006, 1.0)])  # 12 mm thick, at x = 5 across the straight line y = 0
    # the raw path: along y = 0, a lane change to y = 4 around the wall, and back
    raw = space.dense_path(np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 4.0, 0.0], [6.0, 4.0, 0.0],
                                  [8.0, 0.0, 0.0], [10.0, 0.0, 0.0]]))
    assert path_is_valid(space, wall, raw, 0.01) == -1
    cut = shorten_car_path(space, wall, raw, 1.0, 100.0, 300, NO_CLOCK, np.random.default_rng(0))
    assert cut.reverted > 0
    assert path_is_valid(space, wall, cut.path, 0.01) == -1
    assert np.all(wall.configs_free(cut.path))
