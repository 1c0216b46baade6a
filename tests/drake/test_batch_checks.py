"""Batch checks give the same answers as one-by-one checks, and are counted (#19)."""

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402


def test_parallel_batch_matches_single_checks():
    world = DrakeWorld(load_scene("yaml_scenes/fetch_cans_2.yaml"), visual=False)
    rng = np.random.default_rng(4)
    qs = np.array([world.space.sample(rng) for _ in range(128)])
    n0 = world.checks
    batch = world.configs_free(qs)
    assert world.checks - n0 == len(qs)
    single = np.array([world.config_free(q) for q in qs])
    assert np.array_equal(batch, single)
    assert 0 < batch.sum() < len(qs)  # both answers occur, so agreement means something
