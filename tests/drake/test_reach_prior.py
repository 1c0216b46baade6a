"""The reach prior of a car (issue #33): the disc and the obstacles read from Drake, sound against Drake's checker
and against the planner with the prior off; in the generated lots every blocked kind is dropped."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.bench.families import generate, load_family_scene, parse_key  # noqa: E402
from lazyground.bench.families.lot import REACHABLE, spot_kinds  # noqa: E402
from lazyground.drake.reach_prior import footprint  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.goals import REACH_PRIOR, goal_source_for, reach_prior_drops  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.scene.loader import parse_scene  # noqa: E402
from lazyground.settings import GoalSamplingSettings  # noqa: E402
from tests.counts import BY_COUNTS  # noqa: E402

OFF = GoalSamplingSettings(reach_prior=False)


def scene_path(name: str) -> Path:
    return Path(__file__).resolve().parents[2] / "yaml_scenes" / f"{name}.yaml"


def _X(rpy=(0.0, 0.0, 0.0), xyz=(0.0, 0.0, 0.0)) -> np.ndarray:
    from pydrake.math import RigidTransform, RollPitchYaw

    return RigidTransform(RollPitchYaw(*rpy), list(xyz)).GetAsMatrix4()


def test_footprints_of_shapes_across_the_band():
    from pydrake.geometry import Box, Capsule, Convex, Cylinder, HalfSpace, Sphere  # noqa: F401

    band = (0.0, 1.5)
    yawed = footprint(Box(2.0, 1.0, 1.0), _X((0, 0, 0.5), (3, 4, 0.5)), *band)
    assert yawed.half == (1.0, 0.5) and np.allclose(yawed.distance(np.array([[3 + 2 * math.cos(0.5), 4 + 2 * math.sin(0.5)]])), 1.0)
    on_side = footprint(Box(2.0, 1.0, 3.0), _X((math.pi / 2, 0, 0), (0, 0, 0.5)), *band)  # its y axis upright
    assert on_side.half == pytest.approx((1.0, 1.5))
    assert footprint(Box(2.0, 1.0, 1.0), _X((0.3, 0, 0), (0, 0, 0.5)), *band) is False  # tilted: left out
    assert footprint(Box(2.0, 1.0, 1.0), _X(xyz=(0, 0, 3.0)), *band) is None  # wholly above
    assert footprint(Cylinder(0.4, 1.0), _X(xyz=(1, 1, 0.5)), *band).rounding == 0.4
    assert footprint(Cylinder(0.4, 1.0), _X((math.pi / 2, 0, 0), (1, 1, 0.5)), *band) is False  # lying down
    assert footprint(Sphere(0.5), _X(xyz=(0, 0, 1.8)), *band).rounding == pytest.approx(math.sqrt(0.25 - 0.09))
    assert footprint(Sphere(0.5), _X(xyz=(0, 0, 2.1)), *band) is None
    assert footprint(Capsule(0.3, 1.0), _X(xyz=(0, 0, 2.2)), *band).rounding == pytest.approx(math.sqrt(0.09 - 0.04))
    assert footprint(HalfSpace(), _X(), *band) is False


SHAPES = textwrap.dedent("""\
    name: shapes
    robot:
      model: car
      start: {car_x: 3.0, car_y: 3.0, car_qz: 0.3}
      limits: {car_x: [0, 20], car_y: [0, 14]}
    obstacles:
      - {id: yawed, geometry: {box: [4, 0.3, 1]}, pose: {xyz: [8, 5, 0.5], rpy: [0, 0, 0.7]}}
      - {id: post, geometry: {cylinder: {radius: 0.25, length: 1}}, pose: {xyz: [12, 4, 0.5]}}
      - {id: high_ball, geometry: {sphere: {radius: 0.6}}, pose: {xyz: [6, 10, 1.9]}}
      - {id: ball, geometry: {sphere: {radius: 0.5}}, pose: {xyz: [14, 10, 0.4]}}
      - {id: tilted, geometry: {box: [3, 0.4, 0.4]}, pose: {xyz: [16, 6, 0.6], rpy: [0.4, 0.2, 1.0]}}
      - {id: sign, geometry: {box: [3, 3, 0.2]}, pose: {xyz: [10, 11, 2.5]}}
      - {id: lying_pipe, geometry: {cylinder: {radius: 0.3, length: 3}}, pose: {xyz: [4, 12, 0.3], rpy: [1.5708, 0, 0]}}
    objects:
      - {id: spot, type: parking_spot, geometry: {box: [5.5, 2.6, 0.05]}, pose: {xyz: [17, 11, 0], rpy: [0, 0, 1.5708]}}
    planner: {step_size: 1.0}
    """)


def _worlds():
    yield "shapes", parse_scene(SHAPES, source="shapes.yaml")
    for name in ("parking_1", "parking_2", "parking_3"):
        yield name, load_scene(scene_path(name))
    for key in ("lot:64:2:3", "lot:64:2:0:576", "lot:512:2:0:576"):
        yield key, load_family_scene(key)


@pytest.mark.parametrize("name,scene", list(_worlds()), ids=lambda v: v if isinstance(v, str) else "")
def test_no_valid_configuration_has_its_disc_in_a_blocked_cell(name, scene):
    """Soundness cell by cell: 20,000 uniform configurations in the limits (and 20,000 near the obstacles);
    every one Drake finds collision-free has its disc centre in a free cell."""
    world = DrakeWorld(scene, visual=False)
    prior = world.reach_prior()
    assert prior is not None and prior.start
    rng = np.random.default_rng(0)
    lo, hi = world.space.lower, world.space.upper
    qs = rng.uniform(lo, hi, (20_000, 3))
    near = qs[prior.grid.blocked(prior.centres(qs))]  # blocked: shake them by a few cells to probe the edges
    shaken = near[rng.integers(len(near), size=20_000)] + rng.uniform(-0.5, 0.5, (20_000, 3)) * (1, 1, 2 * np.pi)
    for k, batch in enumerate((qs, np.clip(shaken, lo, hi))):
        free = world.configs_free(batch)
        blocked = prior.grid.blocked(prior.centres(batch))
        assert not np.any(free & blocked), f"{name}: {np.sum(free & blocked)} collision-free configurations in blocked cells"
        assert (free.any() or k) and blocked.any()
    if name == "shapes":
        assert set(prior.left_out) == {"tilted", "lying_pipe"}  # left out: only frees cells


def _in_start_component(prior, path) -> bool:
    """Whether the cell of every configuration's disc centre is in a start component."""
    return all(prior.grid.components(c, c) <= set(prior.start) and prior.grid.components(c, c) for c in prior.centres(path))


@pytest.mark.parametrize("key,seeds,algorithm", [("parking_1", range(6), "rrt"), ("parking_2", range(6), "rrt"),
                                                 ("parking_3", range(6), "rrt"), ("lot:8:2:0", range(6), "bidirectional"),
                                                 ("lot:16:2:4", range(6), "bidirectional"),
                                                 ("lot:8:2:0:576", range(4), "bidirectional")])
def test_with_the_prior_off_the_planner_reaches_only_goals_the_prior_keeps(key, seeds, algorithm):
    """The planner, sampling every region (prior off), reaches only goals the prior keeps, and every
    configuration of its dense path has its disc in the start's component."""
    scene = load_family_scene(key) if parse_key(key) else load_scene(scene_path(key))
    world = DrakeWorld(scene, visual=False)
    prior = world.reach_prior()
    solved = 0
    for seed in seeds:
        report = api.plan(scene, "park", seed=seed, world=world, algorithm=algorithm, reach_prior=False,
                          **{**BY_COUNTS, "max_iterations": 4000})
        if not report.result.solved:
            continue
        solved += 1
        assert prior.keeps(report.result.goal_region), f"seed {seed}: reached {report.result.goal_region.id}, dropped by the prior"
        assert _in_start_component(prior, report.result.path)
        assert not any(st.unreachable for st in report.result.region_stats)  # the prior was off
    assert solved >= len(seeds) - 1


@pytest.mark.parametrize("key", ["lot:64:2:0", "lot:64:2:3", "lot:128:2:7", "lot:64:2:0:576", "lot:512:2:0:576"])
def test_every_blocked_kind_of_the_generated_lots_is_dropped(key):
    scene = load_family_scene(key)
    world = DrakeWorld(scene, visual=False)
    kinds = spot_kinds(generate(parse_key(key)))
    regions = tuple(grounding.ground("park", scene).goal_regions)
    dropped = reach_prior_drops(regions, world)
    for j, r in enumerate(regions):
        assert (j in dropped) is (kinds[r.object] != REACHABLE), f"{r.id} ({kinds[r.object]})"
    assert set(dropped.values()) == {REACH_PRIOR}
    assert {kinds[regions[j].object] for j in dropped} >= {"barrier", "gated"}
    assert reach_prior_drops(regions, world, OFF) == {}
    source = goal_source_for(regions, world)
    open_ = [j for j in range(len(regions)) if not source.region_exhausted(j)]
    assert [regions[j].object for j in open_] == [r.object for r in regions if kinds[r.object] == REACHABLE]


def test_an_arm_has_the_arm_prior_and_it_judges_only_pose_regions():
    """An arm's prior is its hand's balls (tests/drake/test_arm_reach_prior.py); a car's judges only config regions."""
    from lazyground.drake.arm_reach import ArmReach

    world = DrakeWorld(load_scene(scene_path("panda_tabletop")), visual=False)
    assert isinstance(world.reach_prior(), ArmReach)
