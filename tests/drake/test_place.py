"""Pick and place: both steps validated with the carried object, the placement on the
surface and upright, and the fallback to another object when the first cannot be placed."""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from grounding.model import Grounding, Interpretation  # noqa: E402
from grounding.regions import regions_for  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.geometry import rpy_to_matrix  # noqa: E402
from lazyground.tasks import place  # noqa: E402
from lazyground.tasks.place import validate_pick_and_place  # noqa: E402
from lazyground.plan_report import PlanReport  # noqa: E402
from lazyground.report import report_to_json  # noqa: E402
from lazyground.scene import load_scene, parse_scene  # noqa: E402
from lazyground.tasks import Worlds  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
KITCHEN = ROOT / "yaml_scenes/kitchen_put_cup_on_table.yaml"


def on_surface_upright(scene, report, clearance=0.01, tol=0.006):
    obj = scene.object(report.outcome.picked)
    target = scene.object(report.outcome.placement.target)
    X = report.outcome.placement.X_WO
    p, R = np.array(X.xyz), rpy_to_matrix(X.rpy)
    hx, hy, hz = target.geometry.half_extents()
    top = target.pose.xyz[2] + hz
    assert abs(p[2] - (top + clearance + obj.geometry.half_extents()[2])) < tol
    local = (p - np.array(target.pose.xyz)) @ rpy_to_matrix(target.pose.rpy)
    assert abs(local[0]) <= hx and abs(local[1]) <= hy
    assert R[:, 2] @ np.array([0, 0, 1.0]) > np.cos(0.03)  # upright within 0.03 rad


BY_ITERATIONS = {"time_limit": 1e6, "max_iterations": 10_000}  # each step bounded by iterations, never by the clock


def solved_report(scene, request, seeds=range(3), **kw):
    for seed in seeds:
        report = api.plan(scene, request, seed=seed, **{**BY_ITERATIONS, **kw})
        if report.result.solved:
            return report
    pytest.fail(f"{request!r} not solved for seeds {list(seeds)}")


def test_put_a_cup_on_the_table():
    scene = load_scene(KITCHEN)
    report = solved_report(scene, "put a cup on the table")
    assert [s.result.status.value for s in report.steps] == ["solved", "solved"]
    assert report.chosen_object.startswith("cup_") and report.steps[1].attached == report.chosen_object
    assert report.chosen.id == f"place:{report.chosen_object}:table"
    assert validate_pick_and_place(report, scene, report.settings.planner.resolution / 10) == []
    on_surface_upright(scene, report)
    doc = report_to_json(report)
    assert {"steps", "picked", "grasp", "placement"} <= set(doc)
    assert len(doc["steps"]) == 2 and all(s["path"] for s in doc["steps"])
    assert doc["time_s"] >= sum(s["time_s"] for s in doc["steps"]) - 1e-6
    # the pick starts at the scene's start, the lift at the grasp, the place where the lift ends
    start = [scene.robot.start[n] for n in report.joint_names]
    assert np.allclose(report.steps[0].result.path[0], start)
    assert np.allclose(doc["lift"]["path"][0], report.steps[0].result.path[-1])
    assert np.allclose(doc["steps"][1]["path"][0], doc["lift"]["path"][-1])
    assert np.allclose(report.result.path[-1], report.steps[1].result.path[-1])


def blocked_tray_scene():
    """The kitchen plus a tray whose top is fully covered: nothing can be placed on it."""
    text = KITCHEN.read_text()
    text = text.replace(
        "objects:\n",
        "- {id: tray_cover, geometry: {box: [0.3, 0.3, 0.3]}, pose: {xyz: [-0.7, -0.9, 1.05]}}\n"
        "objects:\n- {id: tray, type: table, geometry: {box: [0.3, 0.3, 0.02]}, pose: {xyz: [-0.7, -0.9, 0.89]}}\n",
        1,
    )
    return parse_scene(text, "kitchen+tray", KITCHEN.parent)


def test_fallback_when_the_picked_cup_cannot_be_placed():
    scene = blocked_tray_scene()
    red, green, tray, table = (scene.object(i) for i in ("cup_red", "cup_green", "tray", "table"))
    # cup_red (the easy one) may only go on the covered tray; cup_green (harder) on the table
    interps = []
    for cup, target in ((red, tray), (green, table)):
        iid = f"place:{cup.id}:{target.id}"
        interps.append(Interpretation(iid, "place", (cup.id,), target.id, regions_for(cup, "pick", iid, scene),
                                      regions_for(target, "support", iid, scene)))
    g = Grounding("put a cup somewhere", "place", tuple(interps))
    settings = api.run_settings(scene, **BY_ITERATIONS)
    fell_back = 0
    for seed in range(2):
        outcome = place.run(scene, g, settings, np.random.default_rng(seed), Worlds(scene), seed=seed)
        report = PlanReport(g.request, scene.name, seed, settings, g, outcome.result, outcome.joint_names, 0.0, 0.0, outcome)
        if not report.result.solved:
            continue
        assert report.outcome.picked == "cup_green"
        assert validate_pick_and_place(report, scene, settings.planner.resolution / 10) == []
        if report.outcome.fallbacks:
            assert any(n.startswith("picked cup_red") for n in report.notes), report.notes
            # a cup held at a slant (issue 34's angled grasps) may also fail its lift first: another fallback
            fell_back += any("picked cup_red but could not place it" in n for n in report.notes)
    assert fell_back >= 1


def test_place_plans_in_the_callers_world(monkeypatch):
    """A world passed to api.plan is used for the pick (only the carrying world is built),
    and set-up time is not planning time, as for pick and park."""
    import lazyground.drake.world as drake_world

    scene = load_scene(KITCHEN)
    world = drake_world.DrakeWorld(scene)
    built = []

    class Counting(drake_world.DrakeWorld):
        def __init__(self, *args, **kwargs):
            built.append(kwargs.get("attached"))
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(drake_world, "DrakeWorld", Counting)
    report = solved_report(scene, "put a cup on the table", world=world)
    assert built and all(a is not None for a in built)  # never the robot's own world again
    assert report.steps[1].grasp.object_id == report.chosen_object
    assert report.steps[0].setup_s == 0.0 and 0.0 < report.steps[1].setup_s <= report.setup_s
    assert report.time_s == pytest.approx(report.grounding_s + report.result.time_s)
