"""The reach prior of an arm (issue #33): balls in the hand read from Drake, sound against Drake's checker and
against the planner with the prior off; on generated racks every caged and behind can is dropped."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.bench.families import generate, load_family_scene, parse_key  # noqa: E402
from lazyground.bench.families.rack import BEHIND, CAGED, REACHABLE, WINDOW, can_kinds  # noqa: E402
from lazyground.drake.ik.source import IKGoalSource  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.goals import REACH_PRIOR, goal_source_for, reach_prior_drops  # noqa: E402
from lazyground.geometry import Pose  # noqa: E402
from lazyground.planning.stop import StopCondition  # noqa: E402
from lazyground.regions import WorkspaceRegion  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.settings import GoalSamplingSettings  # noqa: E402
from tests.counts import BY_COUNTS  # noqa: E402

OFF = GoalSamplingSettings(reach_prior=False)
_WORLDS: dict = {}


def _world(name: str):
    """(scene, world), built once per module (a 64-can rack takes a few seconds)."""
    if name not in _WORLDS:
        scene = load_family_scene(name) if parse_key(name) else load_scene(Path(__file__).resolve().parents[2] / "yaml_scenes" / f"{name}.yaml")
        _WORLDS[name] = scene, DrakeWorld(scene, visual=False)
    return _WORLDS[name]


def _regions(name: str) -> tuple:
    """The goal regions of every request the scene expects (one request on a rack)."""
    scene, _ = _world(name)
    return tuple(r for request in dict.fromkeys(e.request for e in scene.expect)
                 for r in grounding.ground(request, scene).goal_regions)


def _centres(prior, frame, qs):
    """Per configuration and ball: (blocked, in a start component)."""
    c = prior.centres(frame, qs)
    balls = [b for b, _ in prior.balls(frame)]
    blocked = np.array([b.grid.blocked(c[:, k]) for k, b in enumerate(balls)]).T
    in_start = np.array([[bool(b.grid.components(p, p) & b.start) for k, (b, p) in enumerate(zip(balls, row))] for row in c])
    return blocked, in_start


@pytest.mark.parametrize("name", ["panda_tabletop", "ur5e_tabletop", "fetch_cans_1", "rack:panda:16:1:0",
                                  "rack:fetch:16:1:2", "rack:panda:64:1:3"])
def test_no_collision_free_configuration_has_a_ball_in_a_blocked_cell(name):
    """Soundness cell by cell: 10,000 uniform configurations, 10,000 shaken from those with a ball in a blocked
    cell (the obstacles' edges), and the valid IK goals of every region (inside the cubbies, at the table):
    every one Drake finds collision-free has each ball centre in a free cell. A valid goal of a region the prior
    drops has a ball outside the start's component."""
    scene, world = _world(name)
    prior = world.reach_prior()
    frame = scene.robot.end_effector
    assert prior is not None and prior.balls(frame) and all(b.start for b, _ in prior.balls(frame))
    rng = np.random.default_rng(0)
    lo, hi = world.space.lower, world.space.upper
    qs = rng.uniform(lo, hi, (10_000, len(lo)))
    blocked, _ = _centres(prior, frame, qs)
    near = qs[blocked.any(axis=1)]
    shaken = np.clip(near[rng.integers(len(near), size=10_000)] + rng.uniform(-0.1, 0.1, (10_000, len(lo))), lo, hi)
    for batch in (qs, shaken):
        free = world.configs_free(batch)
        blocked, _ = _centres(prior, frame, batch)
        assert free.any() and not np.any(free[:, None] & blocked), f"{name}: {np.sum(free[:, None] & blocked)} free in blocked cells"
    regions = _regions(name)
    dropped = reach_prior_drops(regions, world)
    goals = []
    for j, r in enumerate(regions[:48]):
        source = IKGoalSource((r,), world, give_up_after=60, attempts_per_sample=60)
        samples = source.draw(2, np.random.default_rng(j), StopCondition.after(None))
        goals += [(j, s.q) for s in samples]
    assert goals
    blocked, in_start = _centres(prior, frame, np.array([q for _, q in goals]))
    assert not blocked.any()
    for (j, q), inside in zip(goals, in_start):
        if j in dropped:
            assert not inside.all(), f"{regions[j].id}: a valid goal of a dropped region with every ball in the start's component"


@pytest.mark.parametrize("name,seeds,cap", [("panda_tabletop", range(3), 4000), ("ur5e_tabletop", range(3), 4000),
                                            ("fetch_cans_1", range(3), 4000), ("rack:panda:8:1:0", range(3), 12000),
                                            ("rack:fetch:8:1:1", range(3), 12000)])
def test_with_the_prior_off_the_planner_reaches_only_goals_the_prior_keeps(name, seeds, cap):
    """The planner sampling every region (prior off) reaches only regions the prior keeps, and every configuration
    of its path at 0.01 rad has each ball in the start's component."""
    scene, world = _world(name)
    prior = world.reach_prior()
    frame = scene.robot.end_effector
    solved = 0
    for seed in seeds:
        report = api.plan(scene, scene.expect[0].request, seed=seed, world=world, algorithm="bidirectional", reach_prior=False,
                          **{**BY_COUNTS, "max_iterations": cap})
        if not report.result.solved:
            continue
        solved += 1
        assert not any(st.unreachable for st in report.result.region_stats)  # the prior was off
        assert prior.keeps(report.result.goal_region), f"seed {seed}: reached {report.result.goal_region.id}, dropped"
        path = report.result.path
        dense = np.vstack([world.space.discretize(a, b, 0.01) for a, b in zip(path[:-1], path[1:])])
        _, in_start = _centres(prior, frame, dense)
        assert in_start.all()
    assert solved >= len(seeds) - 1


@pytest.mark.parametrize("key", ["rack:panda:4:1:0", "rack:panda:64:1:1", "rack:fetch:16:1:0", "rack:fetch:64:1:3"])
def test_every_caged_and_behind_can_of_a_rack_is_dropped(key):
    """Caged (a closed cubby) and behind (a closed cubby beyond the inner ring) cans: every region dropped. The
    reachable can keeps a region; window cans (a window the palm passes) are not dropped by a rigid hand."""
    scene, world = _world(key)
    kinds = can_kinds(generate(parse_key(key)))
    regions = tuple(grounding.ground("pick up a can", scene).goal_regions)
    dropped = reach_prior_drops(regions, world)
    assert set(dropped.values()) <= {REACH_PRIOR}
    for can, kind in kinds.items():
        mine = [j for j, r in enumerate(regions) if r.object == can]
        if kind in (CAGED, BEHIND):
            assert all(j in dropped for j in mine), f"{can} ({kind})"
        elif kind in (REACHABLE, WINDOW):
            assert any(j not in dropped for j in mine), f"{can} ({kind})"
    assert reach_prior_drops(regions, world, OFF) == {}
    source = goal_source_for(regions, world)
    assert {j for j in range(len(regions)) if source.region_exhausted(j)} == set(dropped)


@pytest.mark.parametrize("name", ["panda_tabletop", "ur5e_tabletop", "fetch_cans_1", "fetch_boxes_3"])
def test_bundled_scenes_keep_every_reachable_object(name):
    """Every object a bundled scene expects reachable keeps a region; the Panda's caged can and the cup beyond its
    reach are dropped whole."""
    scene, world = _world(name)
    regions = _regions(name)
    dropped = reach_prior_drops(regions, world)
    for e in scene.expect:
        for obj in e.reachable or ():
            assert any(j not in dropped for j, r in enumerate(regions) if r.object == obj), f"{name}: {obj} dropped"
    if name == "panda_tabletop":
        assert {regions[j].object for j in dropped} >= {"can_caged", "cup_far"}
        assert all(j in dropped for j, r in enumerate(regions) if r.object in ("can_caged", "cup_far"))


def test_a_goal_beyond_the_arms_stretched_length_is_dropped_and_one_within_kept():
    scene, world = _world("panda_tabletop")
    far = WorkspaceRegion("far", "far", "far", (2.0, 0.0, 0.5, 0.0, 0.0, -3.14), (2.1, 0.1, 0.6, 0.0, 0.0, 3.14),
                          frame="panda_hand_tcp", X_WR=Pose())
    near = WorkspaceRegion("near", "near", "near", (0.4, 0.0, 0.5, 0.0, 0.0, -3.14), (0.5, 0.1, 0.6, 0.0, 0.0, 3.14),
                           frame="panda_hand_tcp", X_WR=Pose())
    assert reach_prior_drops((far, near), world) == {0: REACH_PRIOR}


def _one_by_one(prior, region) -> bool:
    """keeps as it was computed before the batch (#33): per region and ball, the box's corners one by one."""
    from lazyground.planning.reach_prior import TOLERANCE, turned_box

    frame, X_ET = region.robot_target(Pose(), None)
    X_WR, X_ST = region.X_WR.matrix(), region.X_SE.matrix() @ X_ET.matrix()
    lower, span, _ = region.unit_map()
    for ball, p_T in prior.balls(frame):
        lo = hi = (X_ST @ np.append(p_T, 1.0))[:3]
        for axis in range(3):
            lo, hi = turned_box(lo, hi, axis, float(lower[3 + axis]), min(float(span[3 + axis]), 2 * np.pi))
        lo, hi = lo + lower[:3], hi + lower[:3] + span[:3]
        corners = np.array([[(lo, hi)[b >> k & 1][k] for k in range(3)] for b in range(8)])
        box = corners @ X_WR[:3, :3].T + X_WR[:3, 3]
        if ball.grid is not None and ball.start and not ball.grid.components(box.min(axis=0) - TOLERANCE,
                                                                            box.max(axis=0) + TOLERANCE) & ball.start:
            return False
    return True


@pytest.mark.parametrize("name", ["panda_tabletop", "ur5e_tabletop", "fetch_boxes_3", "rack:panda:16:1:0",
                                  "rack:fetch:16:1:2", "rack:panda:64:1:3"])
def test_all_regions_at_once_keep_what_one_region_at_a_time_keeps(name):
    """keeps_all (every region's boxes in one pass, #33) answers as the boxes computed one region at a time did."""
    _, world = _world(name)
    regions = _regions(name) if not parse_key(name) else tuple(grounding.ground("pick up a can", _world(name)[0]).goal_regions)
    prior = world.reach_prior()
    prior._kept.clear()
    kept = prior.keeps_all(regions)
    assert kept == [_one_by_one(prior, r) for r in regions]
    assert False in kept and True in kept
    assert [prior.keeps(r) for r in regions] == kept  # cached by the regions' numbers
