"""The fine re-check of candidate paths (#19): one batch per path, each segment checked once per query."""

import numpy as np

from lazyground.planning import PlannerSettings, path_is_valid
from lazyground.planning.search import Search
from tests.unit.toy import REACHABLE, SPACE, WALLS, BoxWorld, goal_source


def test_batched_recheck_finds_the_first_bad_segment_and_shares_vertices():
    world = BoxWorld([[4.0, 0.0, 6.0, 3.0]])
    path = np.array([[1.0, 1.0], [3.0, 1.0], [3.0, 5.0], [7.0, 5.0], [7.0, 1.0], [9.0, 1.0]])
    assert path_is_valid(SPACE, world, path, 0.1) == -1
    # five segments of 20, 40, 40, 40, 20 steps: 160 + 1 configurations, no shared vertex twice
    assert world.checks == 161
    blocked = np.array([[1.0, 1.0], [3.0, 1.0], [7.0, 1.0], [9.0, 1.0]])
    assert path_is_valid(SPACE, world, blocked, 0.1) == 1
    assert path_is_valid(SPACE, world, blocked, 0.1, segments=[2]) == -1  # only the last segment


def test_search_rechecks_each_segment_once():
    world = BoxWorld(WALLS)
    settings = PlannerSettings(step_size=0.5, algorithm="bidirectional")
    s = Search(SPACE, world, goal_source(world, [REACHABLE]), settings, np.random.default_rng(0), 0, False)
    path = np.array([[1.0, 1.0], [1.5, 1.0], [2.0, 1.0]])
    assert s.first_invalid_segment(path) == -1
    n = world.checks
    longer = np.vstack([path, [[2.5, 1.0]]])
    assert s.first_invalid_segment(longer) == -1
    fine = settings.resolution / settings.validation_factor
    assert world.checks - n == len(SPACE.discretize(longer[2], longer[3], fine))  # only the new segment
    assert s.rejected == 0
