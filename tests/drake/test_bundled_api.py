"""#20: ``api.plan("parking_1", "park")`` works from any directory (the README's Python example)."""

from __future__ import annotations

import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning.rrt import path_is_valid  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from tests.counts import BY_COUNTS  # noqa: E402


def test_api_plan_takes_a_bundled_scene_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    report = api.plan("parking_1", "park", seed=3, **BY_COUNTS)
    res = report.result
    assert res.solved, res.message
    assert report.chosen_object in {"spot_b1", "spot_t3", "spot_b9", "spot_t10"}
    world = DrakeWorld(load_scene("parking_1"))
    assert path_is_valid(world.space, world, res.path, report.settings.planner.resolution / 10) == -1
