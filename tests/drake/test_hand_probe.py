"""The hand-alone rejection of IK targets (lazyground.drake.ik.hand_probe, #19): sound and worth having."""

from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground.drake.ik import IKGoalSource, IKSettings  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"
RESTARTS = 8  # IK starts per rejected target: far more than an attempt's 3


@pytest.mark.parametrize("name", ["fetch_boxes_3", "fetch_cans_2"])
def test_no_rejected_target_has_a_free_ik_answer(name):
    """Every target the probe rejects, solved from RESTARTS random starts: no answer within tolerance and limits is free."""
    scene = load_scene(SCENES / f"{name}.yaml")
    world = DrakeWorld(scene, visual=False)
    source = IKGoalSource(grounding.ground(scene.expect[0].request, scene).goal_regions, world, IKSettings(attempt_budget=None))
    rng = np.random.default_rng(5)
    draws = [(r, source.target_poses(np.array([j]), r.sample(rng)[None])[0]) for j, r in enumerate(source.regions) for _ in range(12)]
    X = np.array([X for _, X in draws])
    rejected = X[np.array(source.screen("gripper_link", X)) == "hand in collision"]
    assert len(rejected) >= 0.1 * len(X)  # worth its cost here (boxes_3: ~45 % of the grasp targets)
    starts = np.array([source.random_full(rng) for _ in range(len(rejected) * RESTARTS)])
    answers, ok = source.batch.solver.solve("gripper_link", np.repeat(rejected, RESTARTS, axis=0), starts)
    q = answers[ok][:, source.planned]
    q = q[[world.space.within_bounds(row) for row in q]]
    assert len(q) >= 2 * len(rejected)  # IK meets most rejected targets: the test tests something
    assert not np.any(world.configs_free(q))

