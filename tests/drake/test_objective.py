"""Best, not first (issue #30) on the bundled UR5e tabletop: shortest never returns a longer path than first
from the same seed, and what it returns is valid at the fine resolution."""

import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.tasks.worlds import Worlds  # noqa: E402
from lazyground.bundled import bundled_scene  # noqa: E402

SCENE = load_scene(bundled_scene("ur5e_tabletop"))
# the searches end on these caps, not on the clock (the budget is a backstop)
CAPS = dict(max_iterations=3000, budget=300.0, improve_rounds=3)


@pytest.mark.parametrize("seed", range(3))
def test_shortest_is_no_longer_than_first_and_valid(seed):
    world = Worlds(SCENE, visual=False).get()
    first = api.plan(SCENE, "pick up a cup", seed=seed, world=world, max_iterations=3000)
    best = api.plan(SCENE, "pick up a cup", seed=seed, world=world, objective="shortest", **CAPS)
    assert first.result.solved and best.result.solved
    assert best.result.path_length <= first.result.path_length + 1e-9
    costs = [i.cost for i in best.outcome.improvements]
    assert costs[0] == pytest.approx(first.result.path_length) and costs == sorted(costs, reverse=True)
    planner = best.settings.planner
    assert path_is_valid(world.space, world, best.result.path, planner.resolution / planner.validation_factor) < 0


@pytest.mark.parametrize("seed", range(3))
def test_goals_solved_from_the_start_are_nearer_it(seed):
    """seed_near (what shortest draws after the first solution): every sample of the cup's top grasp is nearer the
    start than the median sample drawn as the first search draws them (random IK branches, any yaw)."""
    import grounding
    import numpy as np

    from lazyground.goals import goal_source_for
    from lazyground.planning.stop import StopCondition

    world = Worlds(SCENE, visual=False).get()
    regions = tuple(r for r in grounding.ground("pick up a cup", SCENE).goal_regions if r.id == "cup_open/top")
    drawn = {}
    for near in (False, True):
        source = goal_source_for(regions, world)
        assert source.seed_near() if near else True
        samples = source.draw(8, np.random.default_rng(seed), StopCondition())
        assert len(samples) == 8
        drawn[near] = [world.space.distance(world.start, g.q) for g in samples]
        assert all(world.config_free(g.q) and world.config_free(g.end) for g in samples)
    assert max(drawn[True]) < np.median(drawn[False])



def test_shortest_in_the_place_task_keeps_both_steps_valid():
    """The objective in a pick and place (tasks.anytime.best_step per step): both steps re-checked with the carried
    object, and a note per step that searched more than once."""
    from lazyground.tasks.place import validate_pick_and_place

    kitchen = load_scene(bundled_scene("kitchen_put_cup_on_table"))
    report = api.plan(kitchen, "put a cup on the table", seed=2, objective="shortest", **CAPS)
    assert report.status == "solved"
    planner = report.settings.planner
    assert validate_pick_and_place(report, kitchen, planner.resolution / planner.validation_factor) == []
    assert any(n.startswith(("pick: best of", "place: best of")) for n in report.notes)
