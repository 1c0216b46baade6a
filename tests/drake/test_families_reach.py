"""Generated families (issue #33): the planner reaches the reachable interpretations only; the blocked
spots' parked poses are collision-free (valid goals), so only the search can tell them apart."""

from __future__ import annotations

import numpy as np
import pytest

import grounding
from lazyground import api
from lazyground.bench.families import generate, load_family_scene, parse_key
from lazyground.bench.families.lot import REACHABLE, spot_kinds
from lazyground.drake.world import DrakeWorld
from lazyground.goals import goal_source_for
from lazyground.planning.search import path_is_valid
from lazyground.planning.stop import StopCondition
from lazyground.settings import GoalSamplingSettings
from lazyground.tasks.car_space import planning_space
from tests.counts import BY_COUNTS


@pytest.mark.parametrize("key,request_,seeds,cap,strategy", [("lot:8:2:0", "park", range(6), 3000, None),
                                                             ("lot:8:2:0:576", "park", range(4), 2000, "cover-connect"),
                                                             ("rack:panda:8:1:0", "pick up a can", range(3), 12000, None)])  # 6 of 6 seeds within 12,000 (angled grasps: more regions per can)
def test_planner_reaches_only_reachable(key, request_, seeds, cap, strategy):
    scene = load_family_scene(key)
    world = DrakeWorld(scene, visual=False)
    reachable = set(scene.expect[0].reachable)
    solved = 0
    for seed in seeds:
        report = api.plan(scene, request_, seed=seed, world=world, algorithm="bidirectional",
                          **{**BY_COUNTS, "max_iterations": cap}, **({"strategy": strategy} if strategy else {}))
        if report.status != "solved":
            continue
        solved += 1
        assert report.chosen.id.split(":")[-1] in reachable
        # finer than the planner's 0.1 m / 0.05 rad, along the car's curves between the dense waypoints: their chords
        # cut a turn's corner by ~0.3 mm, and a path may pass closer than that to a parked car (lot:8:2:0:576 seed 0)
        space = planning_space(scene, world.space, report.settings.planner.kinematics)
        assert path_is_valid(space, world, report.result.path, 0.02) < 0
    assert solved >= len(seeds) - 1


@pytest.mark.parametrize("key", ["lot:64:2:0", "lot:512:2:0:576"])
def test_blocked_spots_have_valid_parked_poses(key):
    scene = load_family_scene(key)
    world = DrakeWorld(scene, visual=False)
    kinds = spot_kinds(generate(parse_key(key)))
    regions = grounding.ground("park", scene).goal_regions
    for kind in set(kinds.values()) - {REACHABLE}:
        spot = next(s for s, k in kinds.items() if k == kind)
        mine = tuple(r for r in regions if r.object == spot)
        source = goal_source_for(mine, world, GoalSamplingSettings(reach_prior=False))  # the prior drops them
        samples = source.draw(3, np.random.default_rng(0), StopCondition.after(None))
        assert samples, f"{kind} spot {spot} has no collision-free parked pose"


@pytest.mark.real_clock  # wiring only: a 1 s bench run on the wall clock, either outcome accepted
@pytest.mark.parametrize("planner", ["nearest-first-bidirectional", "multiplexer", "eager-bidirectional", "independent-bidirectional"])
def test_bench_runs_each_baseline_on_a_family_key(planner):
    from lazyground.bench.runner import RunSpec, run

    row = run(RunSpec("lot:8:2", planner, "consecutive", 0.05, 0, 1.0))
    assert row["status"] in ("solved", "timeout"), row["message"]
    assert row["scene"] == "lot_8_2" and float(row["time_s"]) > 0


def test_panda_window_cans_are_valid_and_unreachable():
    """The Panda's window cubbies (pane set back, a hole round link 7): a can's grasps are collision-free
    for some IK answers, yet with no reachable can (rack:panda:8:0:1, 7 window cans, 1 caged) the planner
    never returns a path within its cap."""
    from lazyground.bench.families.rack import WINDOW, can_kinds
    from lazyground.drake.ik.source import IKGoalSource

    key = "rack:panda:8:0:1"
    scene = load_family_scene(key)
    world = DrakeWorld(scene, visual=False)
    kinds = can_kinds(generate(parse_key(key)))
    regions = grounding.ground("pick up a can", scene).goal_regions
    windows = [c for c, k in kinds.items() if k == WINDOW]
    mine = tuple(r for r in regions if r.object == windows[0])
    source = IKGoalSource(mine, world, give_up_after=10**6, attempts_per_sample=3000)  # ~0.5 % of attempts are valid
    samples = source.draw(1, np.random.default_rng(0), StopCondition.after(None))
    assert samples, "no collision-free grasp of a window can in 3000 attempts"
    for seed in range(2):
        report = api.plan(scene, "pick up a can", seed=seed, world=world, algorithm="bidirectional",
                          strategy="cover", max_iterations=1500, time_limit=600.0)
        assert report.result.goal_samples, "the window cans gave the planner no goal samples"
        assert report.status != "solved"
