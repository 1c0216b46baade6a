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


@pytest.fixture(scope="session")
def parking_gif(parking, tmp_path_factory):
    """(path, figure) of the parking report's GIF, rendered once (the costliest viz step): the file for the GIF's
    own tests, the figure it was drawn on (kept open) for the layout tests."""
    from lazyground.viz import plots

    scene, report = parking
    path, closed = tmp_path_factory.mktemp("gif") / "p.gif", []
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(plots.plt, "close", lambda fig=None: closed.append(fig))  # keep it to look at
        plots.animate_parking(report, scene, path)
    return path, closed[0]
