"""The compiled certifier (#31): what it proves free Drake calls free, what it proves colliding Drake calls
colliding, and the checker's edge answers stay Drake's, on a seeded sample of every bundled arm scene
(tools/certifier_soundness.py runs the full count)."""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.drake.certify_check import compare_configs, compare_edges, compare_penetration, compare_sweeps  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

ARMS = sorted(p.stem for p in Path("yaml_scenes").glob("*.yaml") if not p.stem.startswith("parking"))


@pytest.mark.parametrize("scene", ARMS)
def test_claims_agree_with_drake(scene):
    world = DrakeWorld(load_scene(f"yaml_scenes/{scene}.yaml"), visual=False)
    assert world.checker.compiled is not None
    rng = np.random.default_rng(5)
    c = compare_configs(world, rng, 1500)
    assert c.wrong_free == 0 and c.wrong_collides == 0
    # it decides a good share both ways, so agreement means something; the rest goes to Drake
    assert c.proven_free > 0.3 * c.drake_free and c.proven_colliding > 0.3 * (c.configs - c.drake_free)
    assert c.open > 0
    e = compare_edges(world, rng, 60)
    assert e.mismatches == 0 and 0 < e.free < e.edges
    # configurations in sequence (a path checked finely): most free ones proven from an anchor before them
    s = compare_sweeps(world, rng, 4)
    assert s.wrong_free == 0 and s.wrong_collides == 0
    assert s.proven_free > 0.5 * s.drake_free and s.drake_free < s.configs
    # the penetration test (config_unpadded_free): thresholds less the padding
    u = compare_penetration(world, rng, 300)
    if u is not None:
        assert u.wrong_free == 0 and u.wrong_collides == 0
        assert u.proven_free > 0.5 * u.drake_free and u.proven_colliding > 0


def test_edges_at_any_resolution_on_one_checker():
    """With the certifier, one checker steps edges at every resolution (no second Drake world)."""
    world = DrakeWorld(load_scene("yaml_scenes/panda_tabletop.yaml"), visual=False)
    rng = np.random.default_rng(1)
    a, b = world.space.sample(rng), world.space.sample(rng)
    world.edge_free(a, b, 0.05)
    world.edge_free(a, b, 0.01)
    assert not world._extra


def test_the_compile_is_reported_once_per_process():
    """A built world has its kernels; the time they took is reported (part of the build, not of a request)."""
    from lazyground.drake import compiled

    DrakeWorld(load_scene("yaml_scenes/ur5e_tabletop.yaml"), visual=False)
    seconds, fresh = compiled.compile_report()
    assert seconds > 0.0 and isinstance(fresh, bool)
    assert compiled.warm_up() == 0.0  # once per process


def test_a_car_request_loads_the_cars_kernels_in_its_set_up():
    """api.plan on a Reeds-Shepp scene has loaded the car's kernels before its request began (Worlds.warm_kernels),
    and they count in the compile report."""
    from lazyground import api
    from lazyground.drake import compiled

    scene = load_scene("parking_1")
    api.plan(scene, "park", seed=0, max_iterations=5)
    assert compiled.warm_up_car() == 0.0 and compiled.compile_report() is not None


@pytest.mark.parametrize("cell", [0.2, 0.03])
def test_the_obstacle_grid_gives_the_same_codes_and_open_pairs(cell, monkeypatch):
    """The obstacles' grid (#33; on by default from GRID_FROM obstacles) changes no answer: every row's code and
    open pairs, in order, as the test over every obstacle gives them, and every row's of densely stepped segments
    (the sweep, whose anchors' clearances visit the grid's obstacles only), here forced on a bundled scene's 31,
    with ordinary and with tiny cells: an obstacle in many cells is still tested once."""
    from lazyground.drake import sphere_kernels as kernels
    from lazyground.drake.certify_check import sample_configs
    from lazyground.drake.compiled import _above

    world = DrakeWorld(load_scene("yaml_scenes/fetch_boxes_3.yaml"), visual=False)
    blocks = world.checker.certifier.kernel_blocks()
    rng = np.random.default_rng(3)
    q = sample_configs(world, rng, 1500)
    ends = [world.space.sample(rng) for _ in range(16)]
    dense = world.full(np.vstack([world.space.discretize(a, b, 0.005) for a, b in zip(ends[0::2], ends[1::2])]))
    monkeypatch.setattr(kernels, "GRID_CELL", cell)
    out = []
    for grid_from in (10**9, 1):
        fd, idata = kernels.pack(blocks, grid_from)
        assert bool(idata[idata[7 + kernels._NF + 13] + 3]) == (grid_from == 1)  # gdim[3]: the grid is used
        work, pairs = np.zeros(kernels.work_size(idata)), np.full((len(q), 16), -1, np.int64)
        code = kernels.certify_rows(q, fd, idata, work, pairs)
        one = np.full(17, -1, np.int64)
        shifted = [kernels.certify_one(fd, idata, work, one, row, world.padding) for row in q[:300]]
        swept = np.full((len(dense), 16), -1, np.int64)
        sweep = kernels.sweep_rows(dense, fd, idata, work, _above(blocks), swept)
        out.append((code, np.where(code[:, None] > np.arange(16), pairs, -1), shifted, sweep,
                    np.where(sweep[:, None] > np.arange(16), swept, -1)))
    (c0, p0, s0, w0, v0), (c1, p1, s1, w1, v1) = out
    assert (c0 > 0).sum() > 100 and (c0 == kernels.COLLIDES).sum() > 100  # both answers are exercised
    assert (w0 == 0).sum() > 100 and (w0 != 0).sum() > 100
    assert np.array_equal(c0, c1) and np.array_equal(p0, p1) and s0 == s1
    assert np.array_equal(w0, w1) and np.array_equal(v0, v1)


@pytest.mark.parametrize("cell", [0.2, 0.03])
def test_the_grid_lists_every_obstacle_a_sweep_anchor_needs(cell, monkeypatch):
    """The grid's query with room (#33: a sweep anchor's clearance) lists, once each and in ascending order, every
    checked obstacle whose world box comes within the room of the geometry's farthest reach, and none farther
    (the clearance loop skips every obstacle farther than the room plus that pair's reach)."""
    from lazyground.drake import sphere_kernels as kernels

    world = DrakeWorld(load_scene("yaml_scenes/fetch_boxes_3.yaml"), visual=False)
    blocks = world.checker.certifier.kernel_blocks()
    monkeypatch.setattr(kernels, "GRID_CELL", cell)
    G, O = blocks["counts"]["G"], blocks["counts"]["O"]
    grid = kernels.obstacle_grid(blocks, 1)
    views = tuple(np.ascontiguousarray(grid[k]) for k in ("glo", "ginv", "greach", "gdim", "gstart", "gitem"))
    views += (np.ascontiguousarray(grid["gcell"]).reshape(O, 3),)
    ac, ah = (np.ascontiguousarray(blocks[k], float).reshape(3, O) for k in ("ac", "ah"))
    reach2 = np.ascontiguousarray(blocks["reach2"], float).reshape(G, O)
    rng = np.random.default_rng(2)
    lo, hi = (ac - ah).min(axis=1) - 0.5, (ac + ah).max(axis=1) + 0.5
    cand, seen = np.zeros(O), 0
    for c in rng.uniform(lo, hi, (400, 3)):
        d = np.sqrt((np.maximum(np.abs(c[:, None] - ac) - ah, 0.0) ** 2).sum(axis=0))
        for g in range(G):
            r = grid["greach"][g] + kernels.ROOM
            n = kernels._near(g, c[0], c[1], c[2], ac, ah, reach2, views, cand, kernels.ROOM)
            got = cand[:n].astype(int)
            assert np.all(np.diff(got) > 0)
            checked = reach2[g] >= 0.0
            assert set(np.flatnonzero(checked & (d <= r - 1e-9))) <= set(got) <= set(np.flatnonzero(checked & (d <= r + 1e-9)))
            seen += n
    assert seen > 1000  # near obstacles are met
