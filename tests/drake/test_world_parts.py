"""The DrakeWorld facade over its parts: diagram, coordinates, checker (fixed edge resolution), kinematics, reach-map cache."""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.drake.ik import reach  # noqa: E402
from lazyground.drake.checker import DrakeChecker  # noqa: E402
from lazyground.drake.coordinates import coordinates_from_plant  # noqa: E402
from lazyground.drake.diagram import build_diagram, environment_items  # noqa: E402
from lazyground.drake.ik import IKGoalSource  # noqa: E402
from lazyground.drake.ik.reach import reach_key, reach_map  # noqa: E402
from lazyground.drake.world import MAX_EXTRA_CHECKERS, DrakeWorld  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.scene.schema import Geometry  # noqa: E402

SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"


@pytest.fixture(scope="module")
def lot():
    scene = load_scene(SCENES / "parking_1.yaml")
    return scene, DrakeWorld(scene, visual=False)


@pytest.fixture(scope="module")
def cans1():
    scene = load_scene(SCENES / "fetch_cans_1.yaml")
    return scene, DrakeWorld(scene, visual=False)


def _edges(world, n, rng, length=2.0):
    """n random edges of the given length from free configurations."""
    out = []
    while len(out) < n:
        a = world.space.sample(rng)
        if world.config_free(a):
            d = rng.normal(size=len(a))
            out.append((a, world.space.clip(a + length * d / np.linalg.norm(d))))
    return out


def test_a_checker_keeps_the_resolution_it_was_built_with(lot):
    scene, _ = lot
    diagram, robot = build_diagram(scene, visual=False)
    coords = coordinates_from_plant(diagram.plant(), robot, scene)
    checker = DrakeChecker(diagram, robot, coords, padding=0.0, edge_resolution=0.1)
    a, b = coords.start, coords.start + 0.05
    checker.edge_free(a, b, 0.1)
    assert checker.drake.edge_step_size() == 0.1 and checker.edge_resolution == 0.1
    with pytest.raises(ValueError, match="every 0.1, not 0.05"):
        checker.edge_free(a, b, 0.05)
    assert checker.drake.edge_step_size() == 0.1  # never rewritten


def test_a_checker_built_without_one_fixes_it_at_its_first_edge(lot):
    scene, _ = lot
    diagram, robot = build_diagram(scene, visual=False)
    coords = coordinates_from_plant(diagram.plant(), robot, scene)
    checker = DrakeChecker(diagram, robot, coords, padding=0.0)
    assert checker.edge_resolution is None and checker.accepts(0.3)
    checker.edge_fraction(coords.start, coords.start + 0.05, 0.03)
    assert checker.edge_resolution == 0.03 == checker.drake.edge_step_size() and not checker.accepts(0.3)


def test_world_checks_each_resolution_on_its_own_checker_with_the_same_answers(lot):
    scene, _ = lot
    world = DrakeWorld(scene, visual=False, edge_resolution=0.05)
    rng = np.random.default_rng(0)
    edges = _edges(world, 40, rng, length=3.0)
    fine = [world.edge_free(a, b, 0.05) for a, b in edges]
    assert world.checker.drake.edge_step_size() == 0.05 and not world._extra
    coarse = [world.edge_free(a, b, 0.02) for a, b in edges]  # a second checker, built once
    assert list(world._extra) == [0.02] and world.checker.drake.edge_step_size() == 0.05
    assert world._extra[0.02].drake.edge_step_size() == 0.02
    # a finer check never calls a blocked edge free; both agree with dense config checks where they say free
    assert all(f or not c for f, c in zip(fine, coarse))
    for (a, b), free in zip(edges, coarse):
        dense = world.space.discretize(a, b, 0.002)
        if free:
            assert np.all(world.configs_free(dense))
    assert any(not f for f in fine) and any(fine)  # the sample has both kinds of edge
    checks = world.checks
    world.edge_free(*edges[0], 0.02)
    assert world.checks == checks + 1  # counts include every checker's


def test_extra_checkers_are_bounded(lot):
    scene, _ = lot
    world = DrakeWorld(scene, visual=False, edge_resolution=0.05)
    a = world.start
    for res in (0.01, 0.02, 0.03, 0.04, 0.06):
        world.edge_free(a, a + 0.01, res)
    assert MAX_EXTRA_CHECKERS == 3 and list(world._extra) == [0.03, 0.04, 0.06]  # least recently used dropped
    assert world.checks == 5  # the dropped checker's count stays in the total


def test_occupant_comes_from_the_type_and_the_object(lot):
    scene, world = lot
    spot = next(o for o in scene.objects if o.occupied)
    items = {name: (g, pose) for name, g, pose, _ in environment_items(scene)}
    g, pose = items[f"{spot.id}.parked_car"]
    assert g.box == (4.5, 1.8, 1.5) and pose.xyz[2] == pytest.approx(0.75)
    small = replace(spot, occupant=Geometry(box=(2.0, 1.0, 1.0)))
    other = replace(scene, objects=tuple(small if o.id == spot.id else o for o in scene.objects))
    g, pose = {n: (g, p) for n, g, p, _ in environment_items(other)}[f"{spot.id}.parked_car"]
    assert g.box == (2.0, 1.0, 1.0) and pose.xyz[:2] == spot.pose.xyz[:2] and pose.xyz[2] == pytest.approx(0.5)
    # the collision geometry follows: 3.5 m along the spot from its centre, the car's back overlaps
    # the default parked car (4.5 m long) and clears the 2 m one
    x, y, _ = spot.pose.xyz
    yaw = spot.pose.rpy[2]
    q = np.array([x + 3.5 * np.cos(yaw), y + 3.5 * np.sin(yaw), yaw])
    parked = f"{spot.id}.parked_car"
    assert any(parked in pair for pair in world.colliding_pairs(q))
    assert not any(parked in pair for pair in DrakeWorld(other, visual=False).colliding_pairs(q))


def test_one_forward_kinematics_for_world_and_ik(cans1):
    scene, world = cans1
    source = IKGoalSource((), world)
    rng = np.random.default_rng(2)
    for _ in range(5):
        q = world.space.sample(rng)
        X_world = world.frame_pose("gripper_link", q).matrix()
        X_ik = source.frame_pose("gripper_link", world.full(q))
        assert np.allclose(X_world, X_ik, atol=1e-12)
    X0 = world.frame_pose("gripper_link", world.start).matrix()
    q = world.start.copy()
    q[0] += 0.3  # the first planned joint moves the gripper
    assert not np.allclose(world.frame_pose("gripper_link", q).matrix(), X0)


def test_reach_maps_are_cached_by_what_they_depend_on_and_bounded(cans1, monkeypatch):
    scene, world = cans1
    monkeypatch.setattr(reach, "_REACH_MAPS", type(reach._REACH_MAPS)())
    built = []
    monkeypatch.setattr(reach, "_build_reach_map", lambda w, frame: built.append(frame) or object())
    m = reach_map(world, "gripper_link")
    assert reach_map(world, "gripper_link") is m and built == ["gripper_link"]
    twin = DrakeWorld(scene, visual=False)  # the same robot in a second world shares the map
    assert reach_key(twin, "gripper_link") == reach_key(world, "gripper_link") and reach_map(twin, "gripper_link") is m
    moved = replace(scene, robot=replace(scene.robot, base=replace(scene.robot.base, xyz=(0.5, 0.0, 0.0))))
    assert reach_key(DrakeWorld(moved, visual=False), "gripper_link") != reach_key(world, "gripper_link")
    monkeypatch.setattr(reach, "REACH_CACHE_SIZE", 2)
    reach_map(world, "wrist_roll_link")
    reach_map(world, "wrist_flex_link")
    assert len(reach._REACH_MAPS) == 2 and built == ["gripper_link", "wrist_roll_link", "wrist_flex_link"]
    assert reach_map(world, "gripper_link") is not m  # evicted, built again
