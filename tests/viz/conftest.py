"""Shared fixtures: one planned parking report (seeded), reused by every viz test."""

from pathlib import Path

import pytest

pytest.importorskip("pydrake")

REPO = Path(__file__).resolve().parents[2]
PARKING = REPO / "yaml_scenes" / "parking_1.yaml"


@pytest.fixture(scope="session")
def parking():
    """(scene, report) of "park" on parking_1, seed 0, with the tree kept."""
    from lazyground import api
    from lazyground.scene import load_scene

    scene = load_scene(PARKING)
    report = api.plan(scene, "park", seed=0, keep_tree=True, time_limit=1e6, max_iterations=2_000,
                      kinematics="holonomic")  # the sliding car: its path is shortcut and timed (#16)  # by seed, not clock
    assert report.result.solved, report.result.message
    return scene, report
