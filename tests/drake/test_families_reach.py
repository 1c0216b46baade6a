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
from tests.counts import BY_COUNTS


@pytest.mark.parametrize("key,request_,seeds,cap,strategy", [("lot:8:2:0", "park", range(6), 3000, None),
                                                             ("lot:8:2:0:576", "park", range(1, 5), 2000, "cover-connect"),
                                                             ("rack:panda:8:1:0", "pick up a can", range(3), 5000, None)])
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
        assert path_is_valid(world.space, world, report.result.path, 0.02) < 0  # finer than the planner's 0.1 m / 0.05 rad
    assert solved >= len(seeds) - 1


@pytest.mark.xfail(strict=True, reason="known bug (#33, lots): seed 0's returned path grazes parked_0_s21 (a 4 cm span "
                   "at dense waypoint 843, found at 0.02 and 0.005 m) although the planner's 0.01 m curve re-check passed it")
def test_fixed_lot_seed_0_path_passes_the_fine_recheck():
    scene = load_family_scene("lot:8:2:0:576")
    world = DrakeWorld(scene, visual=False)
    report = api.plan(scene, "park", seed=0, world=world, algorithm="bidirectional", strategy="cover",
                      **{**BY_COUNTS, "max_iterations": 2000})
    assert report.status == "solved"
    assert path_is_valid(world.space, world, report.result.path, 0.02) < 0


@pytest.mark.parametrize("key", ["lot:64:2:0", "lot:512:2:0:576"])
def test_blocked_spots_have_valid_parked_poses(key):
    scene = load_family_scene(key)
    world = DrakeWorld(scene, visual=False)
    kinds = spot_kinds(generate(parse_key(key)))
    regions = grounding.ground("park", scene).goal_regions
    for kind in set(kinds.values()) - {REACHABLE}:
        spot = next(s for s, k in kinds.items() if k == kind)
        mine = tuple(r for r in regions if r.object == spot)
        source = goal_source_for(mine, world)
        samples = source.draw(3, np.random.default_rng(0), StopCondition.after(None))
        assert samples, f"{kind} spot {spot} has no collision-free parked pose"


@pytest.mark.real_clock  # wiring only: a 1 s bench run on the wall clock, either outcome accepted
@pytest.mark.parametrize("planner", ["nearest-first-bidirectional", "multiplexer", "eager-bidirectional", "independent-bidirectional"])
def test_bench_runs_each_baseline_on_a_family_key(planner):
    from lazyground.bench.runner import RunSpec, run

    row = run(RunSpec("lot:8:2", planner, "consecutive", 0.05, 0, 1.0))
    assert row["status"] in ("solved", "timeout"), row["message"]
    assert row["scene"] == "lot_8_2" and float(row["time_s"]) > 0
