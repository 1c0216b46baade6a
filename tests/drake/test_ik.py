"""IK goal sampling (lazyground.drake.ik) on the Fetch scenes."""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.drake.ik import IKGoalSource, IKSettings, reach_map, region_coordinates  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.geometry import Pose  # noqa: E402
from lazyground.planning.rrt import path_is_valid  # noqa: E402
from lazyground.planning.stop import FakeClock, StopCondition  # noqa: E402
from lazyground.regions import PlacementRegion, WorkspaceRegion  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

NO_DEADLINE = StopCondition()  # goal sampling bounded by attempts and restarts, never by the clock

SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"


@pytest.fixture(scope="module")
def cans1():
    scene = load_scene(SCENES / "fetch_cans_1.yaml")
    return scene, DrakeWorld(scene)


@pytest.fixture(scope="module")
def boxes3():
    scene = load_scene(SCENES / "fetch_boxes_3.yaml")
    return scene, DrakeWorld(scene)


@pytest.mark.parametrize("name,request_text", [("fetch_cans_1", "pick up a can"), ("fetch_boxes_3", "pick up a box")])
def test_region_samples_lie_in_their_regions(name, request_text):
    scene = load_scene(SCENES / f"{name}.yaml")
    rng = np.random.default_rng(7)
    for region in grounding.ground(request_text, scene).goal_regions:
        obj = scene.object(region.object)
        centre = np.asarray(obj.pose.xyz)
        for _ in range(20):
            v = region.sample(rng)
            assert region.contains(v)
            X = region.pose_in_world(v).matrix()
            assert region.contains(region_coordinates(region, X), tol=1e-6)
            # grasps sit on the object: within its half-diagonal plus the grasp depth of its centre
            assert np.linalg.norm(X[:3, 3] - centre) <= np.linalg.norm(obj.geometry.half_extents()) + 0.03
        if region.label == "top":  # approach axis straight down
            assert np.allclose(region.pose_in_world(region.sample(rng)).rotation()[:, 0], [0, 0, -1], atol=1e-9)


def _check_samples(source, world, samples, settings):
    assert samples, "no valid goal sample"
    for s in samples:
        region = source.regions[s.region]
        q_full = world.full(s.end)  # the goal configuration; s.q is the pre-pose the planner aims at
        if s.final is not None:  # the pre-pose sits back along the approach, within IK tolerance
            X_pre = source.frame_pose(region.frame, world.full(s.q))
            back = np.linalg.norm(X_pre[:3, 3] - source.frame_pose(region.frame, q_full)[:3, 3])
            assert abs(back - s.extra["approach_scale"] * np.linalg.norm(region.approach)) < 0.01
            assert world.config_free(s.q)
        X = source.frame_pose(region.frame, q_full)
        dp, angle = source.pose_error(region.frame, q_full, s.extra["X_WG"])
        assert dp <= 1.1 * np.sqrt(3) * settings.position_tolerance and angle <= 1.1 * settings.orientation_tolerance
        # the solved pose lies within the IK tolerance of a pose of the region (measured on poses: roll-pitch-yaw
        # stretches a rotation by up to 1 / cos(pitch), an angled grasp's tilt); orientation within 1.1 x its tolerance
        # (the 10 % solver slack): 0.01 flat failed a legitimate 0.0101 rad yaw once cans got side grasps (#15)
        dp, angle = region.pose_error(X)
        assert dp <= 1.1 * np.sqrt(3) * settings.position_tolerance and angle <= 1.1 * settings.orientation_tolerance, (region.id, dp, angle)
        assert world.space.within_bounds(s.end) and world.config_free(s.end)


def test_ik_solutions_satisfy_their_regions(cans1, boxes3):
    settings = IKSettings(attempt_budget=None)  # restarts only: the samples depend on the seed, not the load
    for (scene, world), request_text in ((cans1, "pick up a can"), (boxes3, "pick up a box")):
        source = IKGoalSource(grounding.ground(request_text, scene).goal_regions, world, settings)
        samples = source.draw(6, np.random.default_rng(3), NO_DEADLINE)
        _check_samples(source, world, samples, settings)
        assert {s.region for s in samples} != {samples[0].region} or len(samples) == 1  # round robin spreads them


def test_reach_filter_keeps_reachable_and_rejects_far_targets(cans1):
    scene, world = cans1
    m = reach_map(world, "gripper_link")
    assert np.allclose(m.p_EW, [-0.30495, 0, 0], atol=1e-6)  # Fetch: the wrist flex joint, 0.1385 + 0.16645 behind
    down = Pose((0.4, 0.5, 0.79), (0.0, np.pi / 2, 0.0)).matrix()  # above Can3 on the table, pointing down
    assert m.plausible(down, 0.08)
    assert not m.plausible(Pose((2.0, 0.0, 0.8)).matrix(), 0.08)


def _far_region(frame="gripper_link"):
    return WorkspaceRegion(id="far/top", interpretation="pick:far", object="far",
                           lower=(0, 0, 0, -np.pi, 0, 0), upper=(0, 0, 0, np.pi, 0, 0), frame=frame,
                           X_WR=Pose((1.6, 0.0, 0.8), (0.0, np.pi / 2, 0.0)), label="top")


def test_failed_attempts_are_bounded_by_counts(cans1):
    _, world = cans1
    rng = np.random.default_rng(0)
    filtered = IKGoalSource((_far_region(),), world)
    assert filtered.attempt(0, rng, NO_DEADLINE) == (None, "out of reach")
    assert filtered.counters.solves == 0  # the reach map answers without a solve
    settings = IKSettings(reach_check=False, attempt_budget=None)
    slow = IKGoalSource((_far_region(),), world, settings)
    for k in range(1, 4):  # without a time budget an attempt is exactly `restarts` solves
        assert slow.attempt(0, rng, NO_DEADLINE) == (None, "ik failed")
        assert slow.counters.solves == k * settings.restarts and slow.counters.successes == 0
    # the time budget and the deadline cut an attempt short; an expired one before any solve
    for budget, deadline in ((0.0, StopCondition(clock=FakeClock())), (None, StopCondition.after(-1.0, clock=FakeClock()))):
        cut = IKGoalSource((_far_region(),), world, IKSettings(reach_check=False, attempt_budget=budget))
        assert cut.attempt(0, rng, deadline) == (None, "time") and cut.counters.solves == 0


def test_placement_regions_need_an_attached_object(cans1):
    _, world = cans1
    region = PlacementRegion(id="table/surface", interpretation="place", object="table_right",
                             lower=(0, 0, 0, 0, 0, 0), upper=(0, 0, 0, 0, 0, 0))
    with pytest.raises(ValueError, match="attached"):
        IKGoalSource((region,), world).target_pose_for(region, np.zeros(6))


def test_pick_up_a_can_end_to_end(cans1):
    scene, world = cans1
    report = api.plan(scene, "pick up a can", seed=3, world=world, time_limit=1e6, max_iterations=12_000)  # seed 3: 301
    res = report.result
    assert res.solved, res.message
    assert report.chosen_object in ("Can3", "Can4")  # Can1/Can2 sit deep in shelf 1
    assert path_is_valid(world.space, world, res.path, report.settings.planner.step_size / 100) == -1
    assert np.allclose(res.path[0], world.start) and np.allclose(res.path[-1], res.goal.end)
    region = res.goal_region
    v = region_coordinates(region, IKGoalSource((region,), world).frame_pose(region.frame, world.full(res.goal.end)))
    assert region.contains(v, tol=0.01)


def test_samples_of_one_region_are_not_copies_of_one_ik_branch(boxes3):
    # Resampling only helps the planner if new samples can be new ways in: the samples of one
    # region must spread over the region's IK branches, not sit on the last solution's.
    scene, world = boxes3
    regions = grounding.ground("pick up a box", scene).goal_regions
    source = IKGoalSource(regions, world)
    samples = source.draw(40, np.random.default_rng(0), NO_DEADLINE)
    nearest = []
    for j in {s.region for s in samples}:
        q = np.array([s.q for s in samples if s.region == j])
        if len(q) > 1:
            d = np.linalg.norm(q[:, None] - q[None], axis=2)
            np.fill_diagonal(d, np.inf)
            nearest += list(d.min(axis=1))
    assert len(nearest) >= 10
    assert np.median(nearest) > 0.3  # rad; warm-started samples measured 0.02
