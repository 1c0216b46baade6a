"""The numpy kinematic chain against Drake, and the reach map built with it."""

import numpy as np
import pytest
from pydrake.multibody.tree import JacobianWrtVariable

from lazyground.drake.chain import chain_to_frame
from lazyground.drake.world import DrakeWorld
from lazyground.scene import load_scene


@pytest.fixture(scope="module")
def fetch():
    world = DrakeWorld(load_scene("yaml_scenes/fetch_cans_1.yaml"), visual=False)
    frame = world.plant.GetFrameByName("gripper_link")
    return world, frame, chain_to_frame(world.plant, frame)


def test_chain_pose_and_jacobian_match_drake(fetch):
    world, frame, chain = fetch
    plant = world.plant
    context = plant.CreateDefaultContext()
    rng = np.random.default_rng(0)
    for _ in range(25):
        q = world.q_full.copy()
        q[world.planned] = world.space.sample(rng)
        X, J = chain.forward(q[chain.index], jacobian=True)
        plant.SetPositions(context, q)
        X_drake = plant.CalcRelativeTransform(context, plant.world_frame(), frame).GetAsMatrix4()
        J_drake = plant.CalcJacobianSpatialVelocity(context, JacobianWrtVariable.kQDot, frame, np.zeros(3),
                                                    plant.world_frame(), plant.world_frame())
        np.testing.assert_allclose(X[0], X_drake, atol=1e-12)
        np.testing.assert_allclose(J[0], J_drake[:, chain.index], atol=1e-12)


def test_reach_map_points_are_the_plants_wrist_positions(fetch):
    """The batched reach map holds exactly what asking the plant sample by sample gives."""
    from lazyground.drake.ik import reach

    world, frame, _ = fetch
    built = reach._build_reach_map(world, "gripper_link")
    rng = np.random.default_rng(reach.REACH_SEED)
    wrist = world.plant.GetFrameByName("wrist_flex_link")  # the Fetch's wrist point (roll-flex-roll)
    for k in range(5):
        q = world.q_full.copy()
        q[world.planned] = world.space.sample(rng)
        p = world.kinematics.X_WF(wrist, q).translation()
        np.testing.assert_allclose(built.tree.data[k], p, atol=1e-12)
