"""Returned car paths on the parking scenes are drivable (issue #17).

Every sample of every returned Reeds-Shepp / Dubins path: at most 0.1 m from the next,
the rear axle moving along the heading (forwards or reverse), curvature at most
1 / r_min, the gear changes and driven length as reported; and an independent fine
collision re-check on the dense samples (not only on the planner's waypoints). Runs
are bounded by iterations, not by the clock.
"""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402
from lazyground.planning.car import DENSE_SPACING, CarSpace  # noqa: E402
from lazyground.tasks.car_space import planning_space  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"
UNBOUNDED = dict(time_limit=1e6, max_iterations=20_000)


def assert_drivable(space: CarSpace, path: np.ndarray) -> None:
    steps = np.diff(path, axis=0)
    assert np.all(np.hypot(steps[:, 0], steps[:, 1]) <= DENSE_SPACING + 1e-9), "samples too far apart"
    ref = space.reference(path)
    d = np.diff(ref[:, :2], axis=0)
    chord = np.hypot(d[:, 0], d[:, 1])
    turn = (np.diff(ref[:, 2]) + np.pi) % (2 * np.pi) - np.pi
    moving = chord > 1e-9
    mid = ref[:-1, 2] + 0.5 * turn  # an arc's chord points along the heading halfway through it
    sideways = d[:, 0] * np.sin(mid) - d[:, 1] * np.cos(mid)
    assert np.all(np.abs(sideways[moving]) <= 1e-9 + 1e-6 * chord[moving]), "a step off the heading"
    assert np.all(np.abs(turn[moving]) <= chord[moving] / space.radius * (1 + 1e-3) + 1e-9), "turns tighter than r_min"
    assert np.all(np.abs(turn[~moving]) <= 1e-9), "turns on the spot"


@pytest.mark.parametrize("name,kinematics,seeds", [
    ("parking_1", "reeds-shepp", range(3)),
    ("parking_2", "reeds-shepp", range(2)),
    ("parking_3", "reeds-shepp", range(2)),
])
def test_returned_car_paths_are_drivable_and_free(name, kinematics, seeds):
    scene = load_scene(SCENES / f"{name}.yaml")
    world = DrakeWorld(scene, visual=False)
    space = planning_space(scene, world.space, kinematics)
    solved = 0
    for seed in seeds:
        report = api.plan(scene, "park", seed=seed, world=world, kinematics=kinematics, **UNBOUNDED)
        res = report.result
        if not res.solved:
            continue
        solved += 1
        path = res.path
        assert np.allclose(path[0], world.start) and res.goal_region.contains(path[-1])
        assert_drivable(space, path)
        assert report.cusps == space.cusps(path)
        driven = np.hypot(*np.diff(space.reference(path)[:, :2], axis=0).T).sum()
        assert driven == pytest.approx(res.path_length, rel=1e-3)  # chords of 0.1 m arcs: within 1e-3
        # the motion reports the same driven metres (its line and JSON once gave the raw path in metres and
        # the shortened one in (x, y, heading) units: "33.016 -> 33.908 (shortened)")
        short = report.motion.shortcut
        assert short.length == pytest.approx(res.path_length) and short.length <= short.raw_length
        # the re-check of the dense samples, along the curves between them (what the car drives), at 1/10 of the
        # edge resolution: the configurations the planner's fine check took (CarSpace.discretize)
        fine = report.settings.planner.resolution / 10
        assert path_is_valid(space, world, path, fine) == -1, f"seed {seed}: collides between samples"
    assert solved == len(seeds)


def test_holonomic_mode_is_the_papers_puck():
    scene = load_scene(SCENES / "parking_1.yaml")
    world = DrakeWorld(scene, visual=False)
    report = api.plan(scene, "park", seed=0, world=world, kinematics="holonomic", **UNBOUNDED)
    assert report.result.solved and report.cusps is None
    assert report.settings.planner.kinematics == "holonomic"
    assert planning_space(scene, world.space, "holonomic") is world.space
