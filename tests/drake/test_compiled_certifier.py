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
