"""The task registry and the typed outcome (no Drake: worlds are stand-ins)."""

import dataclasses

import numpy as np
import pytest

from lazyground import tasks
from lazyground.geometry import Pose
from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.plan_report import PlanReport
from lazyground.tasks import Grasp, Lift, Outcome, Step, Worlds


def _result(status=PlanStatus.SOLVED):
    return PlanResult(status, 0, np.zeros((2, 3)), None, None, 1, 2, [], 0, 0.5, 0.1, 0.2)


def test_every_action_grounding_produces_has_a_task():
    assert set(tasks.TASKS) == {"park", "pick", "place", "several"}  # several: a place grounding with groups (#30)
    for action in tasks.TASKS:
        assert callable(tasks.task(action))


def test_an_unknown_action_is_one_clear_error():
    with pytest.raises(ValueError, match="no task for action 'fly' \\(known: park, pick, place, several\\)"):
        tasks.task("fly")


def test_worlds_return_the_callers_world_and_count_no_setup():
    world = object()
    worlds = Worlds(scene=None, world=world)
    assert worlds.get() is world and worlds.get() is world
    assert worlds.setup_s == 0.0


def test_outcome_is_typed_and_frozen():
    grasp = Grasp("cup", "cup/top", "top", "gripper_link", Pose((1.0, 0.0, 0.5)), Pose((0.0, 0.0, 0.1)))
    pick, place = Step("pick cup", _result()), Step("place cup", _result(), 0.3, grasp)
    out = Outcome(_result(), (pick, place), ("a", "b", "c"), lift=Lift(np.zeros((2, 3)), 0.02))
    assert out.picked == "cup" and out.grasp is grasp and place.attached == "cup" and pick.attached is None
    assert pick.trajectory is None  # the slot issue #16 fills
    with pytest.raises(dataclasses.FrozenInstanceError):
        out.fallbacks = 2  # type: ignore[misc]
    report = PlanReport("put a cup on the table", "s", 0, None, None, out.result, out.joint_names, 0.25, 0.0, out)
    assert report.steps == (pick, place) and report.chosen_object == "cup"
    assert report.time_s == pytest.approx(0.75)  # grounding + planning, never set-up
    single = dataclasses.replace(report, outcome=dataclasses.replace(out, steps=(pick,)))
    assert single.steps == ()  # one-step tasks have no "steps" in their report (JSON unchanged)


def test_a_cars_compiled_curves_load_as_set_up_not_as_the_request(monkeypatch):
    """A Reeds-Shepp car's kernels load (or compile) in the set-up, counted like the world build, so the
    report's total_s (the request as the user waits) does not hold them; other kinematics load nothing."""
    from lazyground.drake import compiled

    ticks = [0.0]
    monkeypatch.setattr("lazyground.tasks.worlds.default_clock", lambda: ticks[0])
    loads = []
    monkeypatch.setattr(compiled, "warm_up_car", lambda: loads.append(1) or ticks.__setitem__(0, ticks[0] + 5.0))
    worlds = Worlds(object(), world=object())
    worlds.warm_kernels("holonomic")
    worlds.warm_kernels("dubins")
    assert (worlds.setup_s, loads) == (0.0, [])
    worlds.warm_kernels("reeds-shepp")
    assert (worlds.setup_s, loads) == (5.0, [1])
