"""Issue 34: goal draws that learn where in a region earlier draws worked (lazyground/regions/learned.py).

A toy region: one yaw over the full turn, valid only in a 12-degree band (a can in an open box: the
fingers pass the walls at few yaws), IK reaching but colliding over a wider band around it, out of
reach elsewhere. Rates over seeds, no clock.
"""

import math

import numpy as np
import pytest

from lazyground.goals import RoundRobinGoalSource
from lazyground.planning.problem import GoalSample
from lazyground.planning.stop import never
from lazyground.regions import ConfigRegion
from lazyground.regions.base import from_unit, unit_maps
from lazyground.regions.learned import REACHED_SCORE, RegionLearner, outcome_score

VALID = (0.5, 0.5 + math.radians(12))
REACHED = (0.1, 1.3)


class Toy(RoundRobinGoalSource):
    """Draws one yaw per attempt through a RegionLearner, as the IK source does."""

    reached_reasons = ("in collision",)

    def __init__(self, regions, learning, **kwargs):
        super().__init__(regions, **kwargs)
        self.learner = RegionLearner(unit_maps(self.regions), learning, angles=(0,))

    def attempt(self, j, rng, stop):
        v = from_unit(*self.regions[j].unit_map(), self.learner.warp([j], rng.random((1, 1)))[0])
        yaw = v[0]
        reason = "" if VALID[0] <= yaw <= VALID[1] else "in collision" if REACHED[0] <= yaw <= REACHED[1] else "out of reach"
        self.learner.record(j, v, outcome_score(reason, self.reached_reasons))
        return (GoalSample(q=v, region=j), "") if not reason else (None, reason)


def _region():
    return ConfigRegion(id="can/top", interpretation="pick:can", object="can", lower=(-math.pi,), upper=(math.pi,), wrap=(0,))


def _run(learning: float, seed: int, attempts: int = 200) -> tuple[int, int | None]:
    """(valid samples in ``attempts`` attempts, the attempt that gave the first) for one seed."""
    source = Toy((_region(),), learning, give_up_after=10**6, attempts_per_sample=1)
    rng = np.random.default_rng(seed)
    valid, first = 0, None
    for k in range(attempts):
        got = source.draw(1, rng, never())
        valid += len(got)
        first = k + 1 if got and first is None else first
    return valid, first


def test_without_outcomes_a_draw_is_the_uniform_draw():
    learner = RegionLearner(unit_maps([_region()]), 0.75, angles=(0,))
    u = np.random.default_rng(0).random((50, 1))
    np.testing.assert_array_equal(learner.warp(np.zeros(50, int), u), u)
    learner.record(0, np.array([0.6]), 1.0)
    assert not np.array_equal(learner.warp(np.zeros(50, int), u), u)
    off = RegionLearner(unit_maps([_region()]), 0.0, angles=(0,))
    off.record(0, np.array([0.6]), 1.0)
    np.testing.assert_array_equal(off.warp(np.zeros(50, int), u), u)


def test_draws_stay_in_the_region_and_cover_all_of_it():
    learner = RegionLearner(unit_maps([_region()]), 1.0, angles=(0,))
    for _ in range(100):
        learner.record(0, np.array([0.6]), 1.0)
    u = learner.warp(np.zeros(20000, int), np.random.default_rng(1).random((20000, 1)))
    assert 0.0 <= u.min() and u.max() < 1.0
    hist = np.histogram(u, bins=12, range=(0, 1))[0]
    assert hist.min() > 0  # the prior keeps every bin drawn (1 / 102 of the best bin's weight at least)
    assert hist.argmax() == 7  # yaw 0.6 lies in the eighth of twelve 30-degree bins from -pi


@pytest.mark.parametrize("learning", [0.75])
def test_learned_draws_find_a_narrow_band_more_often(learning):
    seeds = range(40)
    uniform = [_run(0.0, s) for s in seeds]
    learned = [_run(learning, s) for s in seeds]
    rate_u = sum(v for v, _ in uniform) / (200 * len(seeds))
    rate_l = sum(v for v, _ in learned) / (200 * len(seeds))
    assert rate_u < 0.045  # the band is 1/30 of the turn
    assert rate_l > 2 * rate_u, (rate_u, rate_l)
    # the first valid goal within 50 attempts (a region's budget before it is given up)
    within = lambda runs: sum(f is not None and f <= 50 for _, f in runs)  # noqa: E731
    assert within(learned) >= within(uniform), (within(uniform), within(learned))


def test_outcome_scores():
    assert outcome_score("") == 1.0 and outcome_score("in collision") == REACHED_SCORE
    assert outcome_score("out of reach") == 0.0 and outcome_score("hand in collision") == 0.0 and outcome_score("time") is None
