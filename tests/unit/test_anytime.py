"""Best, not first (issue #30): lazyground.tasks.anytime over scripted attempts and the 2-D toy planner."""

from dataclasses import replace

import numpy as np
import pytest

from lazyground.planning import PlannerSettings, PlanStatus, path_is_valid, solve
from lazyground.planning.problem import GoalSample, PlanResult
from lazyground.planning.stop import FakeClock, StopCondition
from lazyground.tasks.anytime import best_of, improvement_notes
from tests.unit.toy import NO_CLOCK, SOLVE_BUDGET, SPACE, START, WALLS, BoxWorld, goal_source, region

NEAR, MID, FAR = region("near", 2.0, 3.0), region("mid", 3.0, 9.0), region("far", 8.0, 9.0)
REGIONS = (NEAR, MID, FAR)
SETTINGS = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, goal_bias=0.1)


class Scripted:
    """An attempt that answers from a script: per call, the region id reached and the path length."""

    def __init__(self, answers, clock=None, seconds=1.0):
        self.answers, self.calls, self.clock, self.seconds = list(answers), [], clock, seconds

    def __call__(self, regions, stop):
        self.calls.append(tuple(r.id for r in regions))
        if self.clock is not None:
            self.clock.advance(self.seconds)
        rid, length = self.answers.pop(0)
        reached = next(r for r in regions if r.id == rid) if rid else None
        status = PlanStatus.SOLVED if reached else PlanStatus.TIMEOUT
        samples = [GoalSample(np.array(r.lower, float), i) for i, r in enumerate(regions)]
        path = np.array([START, np.array(reached.lower, float)]) if reached else None
        return PlanResult(status, 0, path, samples[regions.index(reached)] if reached else None, reached, 5, 5,
                          samples, 0, 1.0, 0.0, 0.0, regions=tuple(regions), path_length=length), None


def test_first_returns_the_first_solution_after_one_search():
    attempt = Scripted([("far", 12.0)])
    best = best_of(attempt, REGIONS, SPACE, START, SETTINGS, StopCondition())
    assert len(attempt.calls) == 1 and best.result.goal_region.id == "far" and len(best.improvements) == 1


def test_shortest_keeps_the_best_tries_other_regions_first_and_prunes_by_the_straight_line():
    # first: far (length 12); then the regions not reached yet; mid's sample is 8 from the start,
    # so once near gives 3.0 mid cannot win and is pruned
    attempt = Scripted([("far", 12.0), ("near", 3.0), ("near", 2.5), ("near", 2.4)])
    settings = replace(SETTINGS, objective="shortest", budget=100.0, improve_rounds=3)
    best = best_of(attempt, REGIONS, SPACE, START, settings, StopCondition())
    assert attempt.calls[0] == ("near", "mid", "far")
    assert attempt.calls[1] == ("near", "mid")  # regions not reached yet
    assert "mid" not in attempt.calls[2] and "far" not in attempt.calls[2]  # both cannot beat 3.0 in a straight line
    assert best.result.path_length == 2.4 and [i.cost for i in best.improvements] == [12.0, 3.0, 2.5, 2.4]
    assert best.searches == 4 and "mid" in best.pruned
    assert best.result.iterations == 20  # counts sum every search
    assert "cost 12.000 -> 2.400" in improvement_notes(best)[0]


def test_the_budget_ends_the_searches_on_the_given_clock():
    clock = FakeClock()
    attempt = Scripted([("far", 12.0)] + [("near", 11.0 - k) for k in range(10)], clock=clock, seconds=1.0)
    settings = replace(SETTINGS, objective="shortest", budget=2.5, improve_rounds=10)
    best = best_of(attempt, REGIONS, SPACE, START, settings, StopCondition.after(100.0, clock=clock))
    assert len(attempt.calls) == 4  # the first, then searches while 2.5 s of budget last (each takes 1 s)
    assert best.improvements[-1].time_s == pytest.approx(4.0)


def test_a_failed_first_search_is_returned_as_it_is():
    best = best_of(Scripted([(None, 0.0)]), REGIONS, SPACE, START, replace(SETTINGS, objective="shortest"),
                   StopCondition())
    assert not best.result.solved and best.searches == 1 and best.improvements == ()


@pytest.mark.parametrize("seed", range(6))
def test_shortest_is_never_longer_than_first_on_the_toy_planner_and_stays_valid(seed):
    world = BoxWorld(WALLS)

    def attempt(settings):
        rng = np.random.default_rng(seed)
        return lambda regions, stop: (solve(SPACE, world, goal_source(world, regions), START, settings, rng, seed=seed,
                                            stop=stop), None)

    first = best_of(attempt(SETTINGS), REGIONS, SPACE, START, SETTINGS, StopCondition(max_iterations=SOLVE_BUDGET))
    shortest_settings = replace(SETTINGS, objective="shortest", budget=NO_CLOCK, improve_rounds=4)
    best = best_of(attempt(shortest_settings), REGIONS, SPACE, START, shortest_settings,
                   StopCondition(max_iterations=SOLVE_BUDGET))
    assert first.result.solved and best.result.solved
    assert best.result.path_length <= first.result.path_length + 1e-9
    assert path_is_valid(SPACE, world, best.result.path, SETTINGS.resolution / 10) < 0


def test_straight_lines_to_drawn_goal_samples_come_first_nearest_first_while_they_can_win():
    tried = []

    def connect(template, sample):
        tried.append(tuple(sample.q))
        region = template.regions[sample.region]
        length = 2.5 if region.id == "near" else 100.0
        return replace(template, goal=sample, goal_region=region, path_length=length), None

    attempt = Scripted([("far", 12.0)])
    settings = replace(SETTINGS, objective="shortest", budget=100.0, improve_rounds=0)
    assert best_of(attempt, REGIONS, SPACE, START, settings, StopCondition(), connect).searches == 1  # 0 rounds: none
    attempt = Scripted([("far", 12.0), (None, 0.0)])
    settings = replace(settings, improve_rounds=1)
    best = best_of(attempt, REGIONS, SPACE, START, settings, StopCondition(), connect)
    assert tried[0] == tuple(NEAR.lower)  # the nearest sample first
    assert best.result.path_length == 2.5 and best.result.goal_region.id == "near"
    assert [i.cost for i in best.improvements] == [12.0, 2.5]


@pytest.mark.parametrize("first_region, first_cost", [("far", 12.0), ("near", 5.0)])
def test_goals_solved_from_the_start_are_asked_of_every_sampled_region_and_tried_in_a_straight_line(
        first_region, first_cost):
    from lazyground.tasks.anytime import NEAR_SAMPLES

    calls = []

    def near(regions, n, stop):  # one goal near the start in region "near", indexed into the regions asked
        calls.append((tuple(r.id for r in regions), n))
        return [GoalSample(np.array([1.5, 2.0]), [r.id for r in regions].index("near"), extra={"near": True})]

    def connect(template, sample):  # only the goals solved from the start are in a straight line
        if not sample.extra.get("near"):
            return None
        region = template.regions[sample.region]
        return replace(template, goal=sample, goal_region=region, path_length=SPACE.distance(START, sample.q)), None

    settings = replace(SETTINGS, objective="shortest", budget=100.0, improve_rounds=1)
    best = best_of(Scripted([(first_region, first_cost), (None, 0.0)]), REGIONS, SPACE, START, settings, StopCondition(),
                   connect, near)
    # mid's and far's samples (7.9, 10.2 away) do not beat 5 in a line, but their branches nearest the start might
    assert calls == [(("near", "mid", "far"), max(NEAR_SAMPLES, 3))]
    assert best.result.goal_region.id == "near" and best.result.path_length == pytest.approx(np.hypot(0.5, 1.0))
    assert [i.cost for i in best.improvements] == [first_cost, pytest.approx(np.hypot(0.5, 1.0))]


def test_a_goal_behind_the_wall_is_joined_to_the_waypoint_past_the_gap():
    from lazyground.tasks.anytime import joined_path

    world = BoxWorld(WALLS)
    path = np.array([START, [3.5, 8.5], [5.5, 8.5], [6.0, 9.5]])  # through the wall's gap, then on
    sample = GoalSample(np.array([6.0, 5.0]), 0)  # beyond the wall: blocked from the start and from (3.5, 8.5)
    joined = joined_path(SPACE, world, path, sample, 0.01, bound=100.0)
    assert joined is not None and np.allclose(joined, [START, [3.5, 8.5], [5.5, 8.5], [6.0, 5.0]])
    assert path_is_valid(SPACE, world, joined, 0.01) < 0
    length = SPACE.path_length(joined)
    assert joined_path(SPACE, world, path, sample, 0.01, bound=length) is None  # cannot beat the bound: not tried
    final = replace(sample, final=np.array([6.5, 5.0]))  # an approach segment is kept after the join
    assert np.allclose(joined_path(SPACE, world, path, final, 0.01, bound=100.0)[-1], [6.5, 5.0])
