"""Full turns of revolute joints (#28): goals nearest the start, sweeps measured across the seam."""

import numpy as np

import pytest

from lazyground.planning import turns as turns_module
from lazyground.planning.turns import nearest_turns, sweep_note, sweeps

TWO_PI = 2 * np.pi


def test_a_goal_most_of_a_turn_away_moves_to_its_equivalent_nearest_the_start():
    lo, hi = -TWO_PI * np.ones(3), TWO_PI * np.ones(3)
    shift = nearest_turns(np.array([5.5, 1.0, -5.0]), np.zeros(3), lo, hi, np.array([True, True, False]))
    assert np.allclose(shift, [-TWO_PI, 0.0, 0.0])  # the third joint is not a revolute angle: left alone


def test_the_limits_and_the_pre_pose_bound_the_shift():
    # the nearest equivalent of 5.5 (-0.78) is below the lower limit -0.5: the goal stays
    assert nearest_turns(np.array([5.5]), np.zeros(1), np.array([-0.5]), np.array([6.0]), np.array([True]))[0] == 0.0
    # a pre-pose that the shift would push out of the limits keeps both where they are
    pre = np.array([6.2])
    shift = nearest_turns(np.array([5.5]), np.array([6.28]), np.array([-1.0]), np.array([12.0]), np.array([True]), (pre,))
    assert shift[0] == 0.0
    shift = nearest_turns(np.array([-0.5]), np.array([6.0]), np.array([-1.0]), np.array([6.2]), np.array([True]), (np.array([-0.1]),))
    assert np.isclose(shift[0], TWO_PI)


def test_sweeps_unwrap_wrapped_angles_and_the_note_names_the_joint():
    path = np.array([[0.0, 3.0, 0.0], [0.0, -3.0, 4.0]])
    assert np.allclose(sweeps(path), [0, 6, 4])
    assert np.allclose(sweeps(path, np.array([False, True, False])), [0, TWO_PI - 6, 4])
    wrap = np.array([False, True, False])
    assert sweep_note(path, ["a", "b", "c"], wrap, np.array([False, True, False])) is None  # c is not an angle: metres are not turns
    assert sweep_note(path, ["a", "b", "c"], wrap, np.array([False, True, True])) == "joint c turns 4.00 rad along the path (more than half a turn)"


def test_an_angle_within_half_a_turn_of_the_start_is_not_searched_and_gets_what_the_search_gives():
    """nearest_turns skips the candidate search where q[i] is within HALF_TURN of the start (#33: ~25 -> ~9 us a
    Fetch goal); the shifts are those of searching every joint, also at and about half a turn apart."""
    rng = np.random.default_rng(0)
    for trial in range(3000):
        lower = -rng.choice([np.pi, 1.5 * np.pi, 2 * np.pi, 3 * np.pi], size=7)
        q, start = lower + rng.random((2, 7)) * -2 * lower
        j = rng.integers(7)
        start[j] = q[j] + rng.choice([-1, 1]) * (np.pi + rng.choice([0.0, 1e-15, -1e-15, 1e-10, -1e-10, 2e-9, -2e-9]))
        turns, together = rng.random(7) < 0.8, (q + 0.05 * rng.normal(size=7),)
        searched = turns_module.nearest_turns(q, start, lower, -lower, turns, together)
        with pytest.MonkeyPatch.context() as m:
            m.setattr(turns_module, "HALF_TURN", -1.0)  # every joint searched
            assert np.array_equal(searched, turns_module.nearest_turns(q, start, lower, -lower, turns, together))
