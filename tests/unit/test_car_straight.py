"""A car's goal tree leaves a tight spot straight along its axis (issue #33): CarSpace.straight_step and
the bidirectional planner's use of it, on a fake checker (no Drake)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from lazyground.goals import ConfigGoalSource
from lazyground.planning import PlannerSettings, birrt, solve
from lazyground.planning.car import CarSpace
from lazyground.planning.tree import Tree
from lazyground.regions import ConfigRegion

R = 3.86
NAMES, WRAP = ("x", "y", "th"), np.array([False, False, True])
LOWER, UPPER = np.array([0.0, -10.0, -math.pi]), np.array([30.0, 20.0, math.pi])


def _space(kinematics="reeds-shepp"):
    return CarSpace(NAMES, LOWER, UPPER, np.array([1.0, 1.0, R]), WRAP, kinematics=kinematics, radius=R)


class SlotWorld:
    """Free everywhere but in a slot x < 6 along y = 0, where only the slot's axis (heading 0) is free."""

    def __init__(self):
        self.check_time, self.checks = 0.0, 0

    def configs_free(self, qs):
        qs = np.atleast_2d(qs)
        self.checks += len(qs)
        in_slot = qs[:, 0] < 6.0
        on_axis = (np.abs(qs[:, 1]) <= 0.05) & (np.abs(np.angle(np.exp(1j * qs[:, 2]))) <= 0.02)
        return ~in_slot | on_axis

    def config_free(self, q) -> bool:
        return bool(self.configs_free(q)[0])


def test_straight_step_goes_along_the_heading_towards_the_target_side():
    space = _space()
    a = np.array([10.0, 5.0, math.pi / 2])
    assert np.allclose(space.straight_step(a, np.array([12.0, 9.0, 0.0]), 2.0), [10.0, 7.0, math.pi / 2])
    assert np.allclose(space.straight_step(a, np.array([8.0, 1.0, 0.0]), 2.0), [10.0, 3.0, math.pi / 2])
    q = space.straight_step(a, np.array([10.0, 9.0, 0.0]), 2.0)
    assert space.distance(a, q) == pytest.approx(2.0)  # a straight curve of the step's length


def test_no_straight_step_out_of_bounds_or_for_a_dubins_car():
    assert _space().straight_step(np.array([1.0, 0.0, 0.0]), np.array([-5.0, 0.0, 0.0]), 2.0) is None
    assert _space().drives_straight and not _space("dubins").drives_straight


def _plan(seed, space):
    world = SlotWorld()
    goal = ConfigRegion(id="slot", interpretation="park:slot", object="slot", lower=(1.0, 0.0, 0.0),
                        upper=(1.0, 0.0, 0.0), wrap=(2,))
    settings = PlannerSettings(step_size=2.0, time_limit=1e6, max_iterations=300, algorithm="bidirectional",
                               strategy="cover-connect", edge_resolution=0.1)
    start = np.array([20.0, 10.0, math.pi / 2])
    return solve(space, world, ConfigGoalSource((goal,), space, world), start, settings, np.random.default_rng(seed))


def test_the_goal_tree_drives_out_of_a_tight_slot(monkeypatch):
    # with straight steps the goal tree is out of the slot in 3 steps: 6-11 iterations (seeds 0-7);
    # with curves only the start tree has to find the slot's axis: 51-269
    with_straight = [_plan(seed, _space()) for seed in range(6)]
    assert all(r.solved and r.iterations <= 30 for r in with_straight)
    monkeypatch.setattr(CarSpace, "straight_step", lambda self, a, towards, step: None)  # curves only
    curves_only = [_plan(seed, _space()).iterations for seed in range(6)]
    assert min(curves_only) > 30


class ClosedSlotWorld(SlotWorld):
    """:class:`SlotWorld` with the slot closed 0.5 m either side of x = 1 (a barrier across its mouth)."""

    def configs_free(self, qs):
        qs = np.atleast_2d(qs)
        return super().configs_free(qs) & ((qs[:, 0] >= 6.0) | (np.abs(qs[:, 0] - 1.0) <= 0.5))


def _stub(space, world):
    return SimpleNamespace(straight_step=space.straight_step if space.drives_straight else None, checker=world,
                           settings=SimpleNamespace(step_size=2.0), motion=space.motion_validator(world), resolution=0.1)


def test_a_goal_sample_that_cannot_drive_a_step_straight_either_way_is_shut_in():
    q = np.array([1.0, 0.0, 0.0])
    assert birrt._shut_in(_stub(_space(), ClosedSlotWorld()), q)
    assert not birrt._shut_in(_stub(_space(), SlotWorld()), q)  # straight forwards out of the open slot
    assert not birrt._shut_in(_stub(_space("dubins"), ClosedSlotWorld()), q)  # no straight steps: never muted


def test_a_muted_root_is_left_out_of_the_forest_queries_but_not_its_own():
    space = _space()
    tree = Tree(space, per_label=True)
    near, far = tree.add_root(np.array([5.0, 5.0, 0.0]), label=0), tree.add_root(np.array([20.0, 5.0, 0.0]), label=1)
    q = np.array([6.0, 5.0, 0.0])
    assert tree.nearest(q) == near
    tree.mute(near)
    assert tree.nearest(q) == far and tree.nearest(q, label=0) == near
