"""The numpy kinematic chain against Drake, and the batched LM IK on it."""

import numpy as np
import pytest
from pydrake.multibody.tree import JacobianWrtVariable

from lazyground.drake.chain import chain_to_frame
from lazyground.drake.lm_ik import LMSettings, rotation_error, solve_lm
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


def test_rotation_error_is_the_rotation_vector():
    angle, axis = 0.7, np.array([0.0, 0.6, 0.8])
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    R_target = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    np.testing.assert_allclose(rotation_error(R_target, np.eye(3)[None])[0], angle * axis, atol=1e-12)


def test_lm_reaches_poses_of_random_configurations_within_tolerance(fetch):
    world, frame, chain = fetch
    rng = np.random.default_rng(1)
    settings = LMSettings()
    solved = 0
    for _ in range(40):
        X_target = chain.forward(world.space.sample(rng))[0]
        starts = np.array([world.space.sample(rng) for _ in range(16)])
        q, converged, _ = solve_lm(chain, X_target, starts, world.space.lower, world.space.upper, world.space.wrap, settings)
        if not converged.any():
            continue
        solved += 1
        X = chain.forward(q[converged])
        assert np.all(np.linalg.norm(X[:, :3, 3] - X_target[:3, 3], axis=1) <= settings.position_tolerance)
        assert np.all(np.linalg.norm(rotation_error(X_target[:3, :3], X[:, :3, :3]), axis=1) <= settings.orientation_tolerance)
        assert np.all(q[converged] >= world.space.lower - 1e-12) and np.all(q[converged] <= world.space.upper + 1e-12)
    assert solved >= 34  # 40 reachable targets: 37 solved with these seeds


def test_lm_reports_no_convergence_for_an_unreachable_pose(fetch):
    world, frame, chain = fetch
    X_target = np.eye(4)
    X_target[:3, 3] = (3.0, 0.0, 1.0)  # 3 m away: beyond the arm
    starts = np.array([world.space.sample(np.random.default_rng(2)) for _ in range(8)])
    _, converged, iterations = solve_lm(chain, X_target, starts, world.space.lower, world.space.upper, world.space.wrap)
    assert not converged.any() and iterations == LMSettings().max_iterations
