"""#20: the JSON states the tolerance IK goals are held to, and the goal configurations meet it."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning.rrt import path_is_valid  # noqa: E402
from lazyground.report import report_to_json  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.tolerance import accepted_error  # noqa: E402
from tests.counts import BY_COUNTS  # noqa: E402


def test_fetch_json_states_the_goal_tolerance_and_the_goal_meets_it():
    scene = load_scene("fetch_cans_1")
    world = DrakeWorld(scene)
    report = api.plan(scene, "pick up the can on the table", seed=3, world=world, **{**BY_COUNTS, "max_iterations": 12_000})  # by seed
    res = report.result
    assert res.solved, res.message
    assert path_is_valid(world.space, world, res.path, report.settings.planner.resolution / 10) == -1
    tol = report_to_json(report)["goal_tolerance"]
    assert tol == {"position_m": pytest.approx(accepted_error()[0], abs=1e-6), "orientation_rad": pytest.approx(accepted_error()[1], abs=1e-6)}
    region, drawn = res.goal_region, res.goal.extra["X_WG"]
    assert region.contains(np.asarray(res.goal.extra["v"]))  # the drawn pose lies in the region ...
    X = world.frame_pose(region.frame, res.path[-1]).matrix()  # ... and the path's end is within tolerance of it
    T = drawn.matrix()
    angle = np.arccos(np.clip((np.trace(T[:3, :3].T @ X[:3, :3]) - 1) / 2, -1, 1))
    assert np.linalg.norm(X[:3, 3] - T[:3, 3]) <= tol["position_m"] and angle <= tol["orientation_rad"]


def test_parking_goals_are_met_exactly_so_no_tolerance_is_stated():
    report = api.plan("parking_1", "park", seed=3, **BY_COUNTS)
    assert report.result.solved
    assert report_to_json(report)["goal_tolerance"] is None
    assert report.result.goal_region.contains(report.result.path[-1])
