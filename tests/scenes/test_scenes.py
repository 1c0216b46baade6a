"""Scene regression tests: every yaml_scenes/*.yaml file's ``expect:`` blocks.

Each block names a request; the test asserts the exact set of interpretations
(when given), a success rate over several seeds (as OMPL's regression tests do,
not exact paths), that solutions reach an allowed object, and re-checks every
returned path and timed trajectory for collisions at one tenth of the planner's
edge resolution.
Every block bounds its runs by ``max_iterations`` (IK attempts by restarts, see
tests/conftest.py), so the outcome of each seed is the same on a loaded machine.
"""

from pathlib import Path

import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.motion.validate import trajectory_problems  # noqa: E402
from lazyground.tasks.place import validate_pick_and_place  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.tasks.car_space import planning_space  # noqa: E402

SCENES = sorted((Path(__file__).resolve().parents[2] / "yaml_scenes").glob("*.yaml"))
CASES = [
    pytest.param(path, k, id=f"{path.stem}[{k}]")
    for path in SCENES
    for k in range(len(load_scene(path).expect))
]


def test_every_scene_has_expectations():
    missing = [p.name for p in SCENES if not load_scene(p).expect]
    assert not missing, f"scenes without an expect: block: {missing}"


def test_every_expectation_is_bounded_by_iterations():
    # A time limit under load turns into flaky failures; an iteration budget gives the same outcome anywhere.
    unbounded = [f"{p.name}[{k}]" for p in SCENES for k, e in enumerate(load_scene(p).expect) if e.max_iterations is None]
    assert not unbounded, f"expect blocks without max_iterations: {unbounded}"


@pytest.mark.parametrize("path,k", CASES)
def test_scene_expectation(path, k):
    scene = load_scene(path)
    expect = scene.expect[k]
    g = grounding.ground(expect.request, scene)
    if expect.interpretations is not None:
        assert {i.id for i in g.interpretations} == set(expect.interpretations)
    world = DrakeWorld(scene)
    overrides = {"time_limit": expect.time_limit, "max_iterations": expect.max_iterations, "strategy": expect.strategy,
                 "algorithm": expect.algorithm, "goal_bias": expect.goal_bias}
    solved = 0
    for seed in range(expect.seeds):
        report = api.plan(scene, expect.request, seed=seed, world=world, **overrides)
        res = report.result
        if not res.solved:
            continue
        solved += 1
        fine = report.settings.planner.resolution / 10
        if report.steps:  # pick and place: both steps, the carried object included
            assert report.chosen_object in (expect.reachable or [report.chosen_object])
            assert validate_pick_and_place(report, scene, fine) == [], f"seed {seed}"
            continue
        if expect.reachable is not None:
            assert report.chosen_object in expect.reachable, f"seed {seed} reached {report.chosen_object}"
        if res.goal_region.kind == "config":
            assert res.goal_region.contains(res.path[-1])
        # along the motion the robot makes: a car's curves between its dense waypoints, not their chords (a chord
        # cuts a turn's corner by ~0.3 mm; parking_2 seed 4 with the reach prior passes closer than that)
        space = planning_space(scene, world.space, report.settings.planner.kinematics)
        assert path_is_valid(space, world, res.path, fine) == -1, f"seed {seed}: path collides at {fine:g}"
        if report.motion is None:  # a car driving Reeds-Shepp curves: its dense path is what it drives (#17)
            assert report.cusps is not None, f"seed {seed}: no timed trajectory"
            continue
        # the timed trajectory too, as a curve (issue #16)
        assert trajectory_problems(report.motion.trajectory, world.space, world, world.start, res.path[-1], fine) == [], f"seed {seed}"
    rate = solved / expect.seeds
    assert rate >= expect.success_rate, f"{expect.request!r}: solved {solved}/{expect.seeds}"
