"""The checker's cheaper paths answer exactly as Drake's own checks, and parallel batches never hang a fork (#19).

``DrakeChecker`` asks SceneGraph's boolean query first, for a configuration and
for an edge's end; both must give Drake's answers configuration by configuration
and edge by edge, including near obstacles, where the padding decides.
"""

from __future__ import annotations

import multiprocessing
import os
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.drake import parallel  # noqa: E402
from lazyground.drake.checker import DrakeChecker  # noqa: E402
from lazyground.drake.edge_kernel import BISECTION, step_order  # noqa: E402
from lazyground.drake.diagram import build_diagram  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"


@pytest.fixture(scope="module", params=["fetch_boxes_3", "parking_1"])
def world(request):
    return DrakeWorld(load_scene(SCENES / f"{request.param}.yaml"), visual=False, edge_resolution=0.05)


def _near_obstacles(world, rng, n):
    """Configurations half-way between a free and a colliding sample, bisected towards the boundary."""
    out = []
    while len(out) < n:
        a, b = world.space.sample(rng), world.space.sample(rng)
        fa, fb = (world.checker.drake.CheckConfigCollisionFree(world.full(q)) for q in (a, b))
        if fa == fb:
            continue
        for _ in range(12):  # ~ the padding's scale after a dozen halvings of a metre-scale edge
            m = world.space.interpolate(a, b, 0.5)
            if world.checker.drake.CheckConfigCollisionFree(world.full(m)) == fa:
                a = m
            else:
                b = m
        out += [a, b]
    return np.array(out)


def test_the_cheap_config_check_is_drakes_answer(world):
    assert world.checker.penetration_first  # the bundled scenes qualify: else this test tests nothing new
    rng = np.random.default_rng(7)
    qs = np.vstack([np.array([world.space.sample(rng) for _ in range(300)]), _near_obstacles(world, rng, 60)])
    drake = np.array([world.checker.drake.CheckConfigCollisionFree(world.full(q)) for q in qs], bool)
    ours = np.array([world.config_free(q) for q in qs])
    assert np.array_equal(ours, drake)
    assert 0 < drake.sum() < len(qs)


def test_the_unpadded_check_is_implied_by_drakes_and_misses_only_padding(world):
    """config_unpadded_free is False only where Drake's check is False too, and True where the robot
    merely comes within the padding (no penetration), so the planner must check the padding later."""
    rng = np.random.default_rng(9)
    qs = np.vstack([np.array([world.space.sample(rng) for _ in range(300)]), _near_obstacles(world, rng, 60)])
    drake = np.array([world.checker.drake.CheckConfigCollisionFree(world.full(q)) for q in qs], bool)
    unpadded = np.array([world.config_unpadded_free(q) for q in qs])
    assert not np.any(drake & ~unpadded)  # never rejects what Drake accepts
    assert np.any(~drake & ~unpadded)  # rejects real collisions
    if world.padding > 0.001:  # fetch_boxes_3 pads 5 mm; parking_1 pads nothing
        assert np.any(~drake & unpadded)  # within the padding: left to the padded check


def test_the_edge_check_is_drakes_answer(world):
    rng = np.random.default_rng(8)
    edges, inside = [], 0
    while len(edges) < 300 or inside < 5:
        a = world.space.sample(rng)
        if not world.checker.drake.CheckConfigCollisionFree(world.full(a)):
            continue
        b, _ = world.space.steer(a, world.space.sample(rng), 0.6)
        fa, fb = world.full(a), world.full(a + world.space.difference(a, b))
        want = world.checker.drake.CheckEdgeCollisionFree(fa, fb)
        inside += not want and world.checker.drake.CheckConfigCollisionFree(fb)  # blocked between the ends
        edges.append((a, b, want))
    got = [world.edge_free(a, b, 0.05) for a, b, _ in edges]
    assert got == [w for _, _, w in edges]
    assert 0 < sum(got) < len(got)


def test_a_negative_padding_keeps_drakes_own_checks():
    scene = load_scene(SCENES / "parking_1.yaml")
    diagram, robot = build_diagram(scene, None, visual=False)
    from lazyground.drake.coordinates import coordinates_from_plant

    coordinates = coordinates_from_plant(diagram.plant(), robot, scene)
    checker = DrakeChecker(diagram, robot, coordinates, padding=-0.01, edge_resolution=0.05)
    assert not checker.penetration_first  # a penetration shallower than the padding is free for Drake
    rng = np.random.default_rng(9)
    qs = [coordinates.space.sample(rng) for _ in range(50)]
    assert [checker.config_free(q) for q in qs] == [bool(checker.drake.CheckConfigCollisionFree(coordinates.full(q))) for q in qs]


def _check_in_child(world, qs, conn):
    conn.send((parallel.parallel_batch(10**6), world.configs_free(qs).tolist()))


def test_a_process_forked_after_a_parallel_batch_checks_serially_and_finishes():
    if os.cpu_count() == 1:
        pytest.skip("one core: no parallel batches")
    world = DrakeWorld(load_scene(SCENES / "fetch_cans_1.yaml"), visual=False)
    rng = np.random.default_rng(10)
    qs = np.array([world.space.sample(rng) for _ in range(parallel.PARALLEL_MIN_BATCH)])
    assert parallel.parallel_batch(len(qs))  # this batch runs on the OpenMP pool
    here = world.configs_free(qs).tolist()
    ctx = multiprocessing.get_context("fork")
    ours, theirs = ctx.Pipe()
    child = ctx.Process(target=_check_in_child, args=(world, qs, theirs))
    child.start()
    # without the at-fork guard the child hangs in its first parallel batch; the timeout only bounds a hang
    assert ours.poll(600), "the forked child hung in its batch check"
    parallel_in_child, there = ours.recv()
    child.join()
    assert not parallel_in_child and there == here


def test_each_single_check_counts_once(world):
    """The reports' check counts (checks, µs per check) rest on one count per call, whatever path answers it."""
    rng = np.random.default_rng(11)
    qs = np.vstack([np.array([world.space.sample(rng) for _ in range(40)]), _near_obstacles(world, rng, 10)])
    for method in (world.checker.config_free, world.checker.config_unpadded_free):
        before = world.checker.checks
        for k, q in enumerate(qs, 1):
            method(q)
            assert world.checker.checks == before + k


@pytest.mark.parametrize("n", range(1, 41))
def test_the_bisection_order_visits_every_step_once_end_first(n):
    """Steps 0..n of an edge, each exactly once, the end n first and the start 0 next (else a step goes
    unchecked, or is checked twice); worked from the docstring's rule, not from the code."""
    order = step_order(n, BISECTION).tolist()
    assert sorted(order) == list(range(n + 1))
    assert order[:2] == [n, 0]
    if n >= 2:
        assert order[2] == n // 2  # the first halving's middle


def test_a_checker_without_certifier_keeps_its_first_edge_resolution():
    """Drake's checker has one edge step size: a second resolution is refused, not silently used as the first."""
    world = DrakeWorld(load_scene(SCENES / "parking_1.yaml"), visual=False)
    assert world.checker.compiled is None and world.checker.edge_resolution is None
    rng = np.random.default_rng(0)
    a, b = world.space.sample(rng), world.space.sample(rng)
    world.checker.edge_free(a, b, 0.05)
    assert world.checker.edge_resolution == 0.05
    world.checker.edge_free(a, b, 0.05)
    with pytest.raises(ValueError, match="every 0.05, not 0.1"):
        world.checker.edge_free(a, b, 0.1)


def test_colliding_pairs_name_obstacles_by_their_scene_names():
    """A pair with a scene obstacle names the obstacle as the scene does (not its body, the world)."""
    scene = load_scene(SCENES / "fetch_boxes_3.yaml")
    world = DrakeWorld(scene, visual=False)
    rng = np.random.default_rng(3)
    names = set()
    for _ in range(100):
        for pair in world.checker.colliding_pairs(world.space.sample(rng)):
            names.update(pair)
    obstacles = {o.id for o in scene.obstacles} | {o.id for o in scene.objects}
    assert "world" not in names
    assert names & obstacles  # random arm configurations hit the shelves: else this test tests nothing
