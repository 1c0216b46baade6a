"""Tests for the primitive-geometry Fetch model in models/fetch/fetch.urdf."""

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from pydrake.geometry import Role  # noqa: E402
from pydrake.multibody.parsing import Parser  # noqa: E402
from pydrake.planning import (  # noqa: E402
    RobotDiagramBuilder,
    SceneGraphCollisionChecker,
)

FETCH_URDF = Path(__file__).resolve().parents[2] / "models" / "fetch" / "fetch.urdf"

# Moving joints, in plant position order, with the published limits.
JOINT_LIMITS = {
    "torso_lift_joint": (0.0, 0.38615),
    "shoulder_pan_joint": (-1.6056, 1.6056),
    "shoulder_lift_joint": (-1.221, 1.518),
    "upperarm_roll_joint": (-math.pi, math.pi),
    "elbow_flex_joint": (-2.251, 2.251),
    "forearm_roll_joint": (-math.pi, math.pi),
    "wrist_flex_joint": (-2.16, 2.16),
    "wrist_roll_joint": (-math.pi, math.pi),
}

# torso, shoulder_pan, shoulder_lift, upperarm_roll, elbow_flex,
# forearm_roll, wrist_flex, wrist_roll
TUCKED = np.array([0.05, 1.32, 1.4, -0.2, 1.72, 0.0, 1.66, 0.0])
ZERO = np.zeros(8)

# Published joint origins (parent frame -> joint), used for an independent FK.
TORSO_ORIGIN = np.array([-0.086875, 0.0, 0.37743])
ARM_CHAIN = [  # (origin in parent, rotation axis)
    (np.array([0.119525, 0.0, 0.34858]), np.array([0.0, 0.0, 1.0])),  # pan
    (np.array([0.117, 0.0, 0.06]), np.array([0.0, 1.0, 0.0])),  # lift
    (np.array([0.219, 0.0, 0.0]), np.array([1.0, 0.0, 0.0])),  # upperarm roll
    (np.array([0.133, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])),  # elbow flex
    (np.array([0.197, 0.0, 0.0]), np.array([1.0, 0.0, 0.0])),  # forearm roll
    (np.array([0.1245, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])),  # wrist flex
    (np.array([0.1385, 0.0, 0.0]), np.array([1.0, 0.0, 0.0])),  # wrist roll
]
GRIPPER_OFFSET = np.array([0.16645, 0.0, 0.0])

# Hand-computed gripper_link position with every joint at zero.
ZERO_GRIPPER_X = (
    -0.086875 + 0.119525 + 0.117 + 0.219 + 0.133 + 0.197 + 0.1245 + 0.1385 + 0.16645
)  # = 1.1281
ZERO_GRIPPER_Z = 0.37743 + 0.34858 + 0.06  # = 0.78601
SHOULDER_PAN_X = -0.086875 + 0.119525  # = 0.03265
SHOULDER_LIFT_X = SHOULDER_PAN_X + 0.117  # = 0.14965


def _rot(axis, angle):
    """Rodrigues rotation matrix."""
    k = np.array(
        [[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]]
    )
    return np.eye(3) + math.sin(angle) * k + (1 - math.cos(angle)) * (k @ k)


def _reference_gripper_pose(q):
    """Independent FK from the published numbers: returns (p_WG, R_WG)."""
    p = TORSO_ORIGIN + np.array([0.0, 0.0, q[0]])
    R = np.eye(3)
    for (origin, axis), angle in zip(ARM_CHAIN, q[1:]):
        p = p + R @ origin
        R = R @ _rot(axis, angle)
    return p + R @ GRIPPER_OFFSET, R


def _build():
    builder = RobotDiagramBuilder(time_step=0.0)
    plant = builder.plant()
    instances = Parser(plant).AddModels(str(FETCH_URDF))
    assert len(instances) == 1
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName("base_link"))
    diagram = builder.Build()
    return diagram, instances[0]


@pytest.fixture(scope="module")
def model():
    diagram, instance = _build()
    plant = diagram.plant()
    context = diagram.CreateDefaultContext()
    return diagram, plant, instance, context


@pytest.fixture(scope="module")
def checker():
    diagram, instance = _build()
    return SceneGraphCollisionChecker(
        model=diagram,
        robot_model_instances=[instance],
        edge_step_size=0.05,
        env_collision_padding=0.005,
        self_collision_padding=0.005,
    )


def _gripper_pose(model, q):
    diagram, plant, _, context = model
    plant_context = plant.GetMyContextFromRoot(context)
    plant.SetPositions(plant_context, np.asarray(q, dtype=float))
    return plant.CalcRelativeTransform(
        plant_context, plant.world_frame(), plant.GetFrameByName("gripper_link")
    )


def _sample(rng, n):
    lower = np.array([lo for lo, _ in JOINT_LIMITS.values()])
    upper = np.array([hi for _, hi in JOINT_LIMITS.values()])
    return rng.uniform(lower, upper, size=(n, len(lower)))


# --------------------------------------------------------------------------
# 1. Loading, joints and limits
# --------------------------------------------------------------------------


def test_urdf_is_self_contained():
    text = FETCH_URDF.read_text()
    # Primitives only: no meshes, no files, no package:// URLs to resolve.
    assert "filename=" not in text
    assert "<mesh" not in text
    # The loader welds base_link; the URDF must not do it itself.
    assert 'link name="world"' not in text


def test_loads_with_eight_named_joints_and_limits(model):
    _, plant, instance, _ = model
    assert plant.num_positions() == 8
    assert plant.num_positions(instance) == 8
    assert plant.num_velocities() == 8

    for index, (name, (lower, upper)) in enumerate(JOINT_LIMITS.items()):
        joint = plant.GetJointByName(name, instance)
        assert joint.num_positions() == 1
        assert joint.position_start() == index
        assert joint.position_lower_limits()[0] == pytest.approx(lower, abs=1e-5)
        assert joint.position_upper_limits()[0] == pytest.approx(upper, abs=1e-5)

    assert plant.GetJointByName("torso_lift_joint").type_name() == "prismatic"
    for name in list(JOINT_LIMITS)[1:]:
        assert plant.GetJointByName(name).type_name() == "revolute"

    for frame in (
        "base_link",
        "torso_fixed_link",
        "torso_lift_link",
        "head_pan_link",
        "gripper_link",
        "l_gripper_finger_link",
        "r_gripper_finger_link",
    ):
        assert plant.HasFrameNamed(frame, instance)


def test_moving_bodies_have_positive_mass(model):
    _, plant, instance, context = model
    plant_context = plant.GetMyContextFromRoot(context)
    for body_index in plant.GetBodyIndices(instance):
        body = plant.get_body(body_index)
        assert body.get_mass(plant_context) > 0.0, body.name()


# --------------------------------------------------------------------------
# 2. Forward kinematics
# --------------------------------------------------------------------------


def test_fk_all_zero(model):
    X = _gripper_pose(model, ZERO)
    np.testing.assert_allclose(
        X.translation(), [ZERO_GRIPPER_X, 0.0, ZERO_GRIPPER_Z], atol=1e-9
    )
    np.testing.assert_allclose(X.translation(), [1.1281, 0.0, 0.78601], atol=1e-9)
    np.testing.assert_allclose(X.rotation().matrix(), np.eye(3), atol=1e-12)


def test_fk_torso_lift_raises_gripper(model):
    q = ZERO.copy()
    q[0] = 0.3
    np.testing.assert_allclose(
        _gripper_pose(model, q).translation(),
        [ZERO_GRIPPER_X, 0.0, ZERO_GRIPPER_Z + 0.3],
        atol=1e-9,
    )


def test_fk_shoulder_pan_quarter_turn_points_along_y(model):
    q = ZERO.copy()
    q[1] = math.pi / 2
    X = _gripper_pose(model, q)
    reach = ZERO_GRIPPER_X - SHOULDER_PAN_X  # 1.09545 from the pan axis
    np.testing.assert_allclose(
        X.translation(), [SHOULDER_PAN_X, reach, ZERO_GRIPPER_Z], atol=1e-9
    )
    np.testing.assert_allclose(X.rotation().matrix()[:, 0], [0, 1, 0], atol=1e-9)


def test_fk_positive_shoulder_lift_pitches_arm_down(model):
    q = ZERO.copy()
    q[2] = math.pi / 2
    X = _gripper_pose(model, q)
    reach = ZERO_GRIPPER_X - SHOULDER_LIFT_X  # 0.97845 from the lift axis
    np.testing.assert_allclose(
        X.translation(),
        [SHOULDER_LIFT_X, 0.0, ZERO_GRIPPER_Z - reach],
        atol=1e-9,
    )
    assert X.translation()[2] < ZERO_GRIPPER_Z
    np.testing.assert_allclose(X.rotation().matrix()[:, 0], [0, 0, -1], atol=1e-9)


def test_fk_matches_independent_chain_at_random_configs(model):
    rng = np.random.default_rng(1234)
    for q in _sample(rng, 25):
        X = _gripper_pose(model, q)
        p_ref, R_ref = _reference_gripper_pose(q)
        np.testing.assert_allclose(X.translation(), p_ref, atol=1e-9)
        np.testing.assert_allclose(X.rotation().matrix(), R_ref, atol=1e-9)


# --------------------------------------------------------------------------
# Gripper geometry: gripper_link is the grasp point between the fingers.
# --------------------------------------------------------------------------


def test_grasp_point_is_clear_of_palm_and_between_fingers(model):
    diagram, plant, _, context = model
    X = _gripper_pose(model, ZERO)
    scene_graph = diagram.scene_graph()
    query = scene_graph.get_query_output_port().Eval(
        scene_graph.GetMyContextFromRoot(context)
    )
    inspector = query.inspector()

    def distances_from(p_W):
        out = {}
        for result in query.ComputeSignedDistanceToPoint(p_W, threshold=0.2):
            body = plant.GetBodyFromFrameId(inspector.GetFrameId(result.id_G))
            out[body.name()] = min(result.distance, out.get(body.name(), 1.0))
        return out

    at_origin = distances_from(X.translation())
    # An object of radius 2.5 cm at the grasp point touches nothing.
    for name in ("gripper_link", "l_gripper_finger_link", "r_gripper_finger_link"):
        assert at_origin[name] > 0.025, (name, at_origin[name])
    assert at_origin["gripper_link"] == pytest.approx(0.03, abs=1e-6)
    assert at_origin["l_gripper_finger_link"] == pytest.approx(0.05, abs=1e-6)
    assert at_origin["r_gripper_finger_link"] == pytest.approx(0.05, abs=1e-6)

    # The palm is behind the grasp point: 5 cm back along -x we are inside it.
    behind = distances_from(X.translation() - 0.05 * X.rotation().matrix()[:, 0])
    assert behind["gripper_link"] < 0.0


def test_every_link_has_collision_and_visual_geometry(model):
    diagram, plant, instance, _ = model
    inspector = diagram.scene_graph().model_inspector()
    for body_index in plant.GetBodyIndices(instance):
        body = plant.get_body(body_index)
        frame_id = plant.GetBodyFrameIdOrThrow(body_index)
        assert inspector.NumGeometriesForFrameWithRole(
            frame_id, Role.kProximity
        ) > 0, body.name()
        assert inspector.NumGeometriesForFrameWithRole(
            frame_id, Role.kIllustration
        ) > 0, body.name()


def test_collision_filters(model):
    diagram, plant, _, _ = model
    inspector = diagram.scene_graph().model_inspector()

    def geometry(body_name):
        frame_id = plant.GetBodyFrameIdOrThrow(plant.GetBodyByName(body_name).index())
        return inspector.GetGeometries(frame_id, Role.kProximity)[0]

    def filtered(a, b):
        return inspector.CollisionFiltered(geometry(a), geometry(b))

    # Explicit URDF filter groups.
    assert filtered("torso_lift_link", "torso_fixed_link")
    assert filtered("gripper_link", "l_gripper_finger_link")
    assert filtered("l_gripper_finger_link", "r_gripper_finger_link")
    assert filtered("wrist_roll_link", "r_gripper_finger_link")
    # Pairs that must stay checked.
    assert not filtered("torso_lift_link", "gripper_link")
    assert not filtered("torso_lift_link", "r_gripper_finger_link")
    assert not filtered("torso_lift_link", "forearm_roll_link")
    assert not filtered("base_link", "wrist_flex_link")
    assert not filtered("head_pan_link", "upperarm_roll_link")
    assert not filtered("shoulder_lift_link", "gripper_link")


# --------------------------------------------------------------------------
# 3./4. Collision checking
# --------------------------------------------------------------------------


def test_tucked_pose_is_collision_free(checker):
    assert checker.CheckConfigCollisionFree(TUCKED)
    tucked_low = TUCKED.copy()
    tucked_low[0] = 0.0
    assert checker.CheckConfigCollisionFree(tucked_low)


def test_zero_pose_is_collision_free(checker):
    assert checker.CheckConfigCollisionFree(ZERO)
    q = ZERO.copy()
    q[0] = JOINT_LIMITS["torso_lift_joint"][1]
    assert checker.CheckConfigCollisionFree(q)


def test_arm_pointing_into_base_collides(checker):
    q = ZERO.copy()
    q[2] = 1.5  # shoulder lift: arm straight down through the base
    assert not checker.CheckConfigCollisionFree(q)


def test_arm_folded_back_into_torso_collides(checker):
    q = ZERO.copy()
    q[2] = 1.5  # arm down ...
    q[4] = 2.2  # ... and the forearm folded back into the torso column
    assert not checker.CheckConfigCollisionFree(q)


def test_distance_between_tucked_gripper_and_torso(model):
    diagram, plant, _, context = model
    _gripper_pose(model, TUCKED)  # sets the positions
    scene_graph = diagram.scene_graph()
    query = scene_graph.get_query_output_port().Eval(
        scene_graph.GetMyContextFromRoot(context)
    )
    inspector = query.inspector()

    def body(geometry_id):
        return plant.GetBodyFromFrameId(inspector.GetFrameId(geometry_id)).name()

    hand = {"gripper_link", "l_gripper_finger_link", "r_gripper_finger_link"}
    clearance = min(
        r.distance
        for r in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=0.2)
        if "torso_lift_link" in (body(r.id_A), body(r.id_B))
        and hand & {body(r.id_A), body(r.id_B)}
    )
    # Tight like the real robot (a couple of cm), but above the 5 mm padding.
    assert 0.005 < clearance < 0.04


def test_random_configurations_mix_free_and_colliding(checker):
    rng = np.random.default_rng(0)
    samples = _sample(rng, 300)
    free = np.array([checker.CheckConfigCollisionFree(q) for q in samples])
    fraction_free = free.mean()
    assert fraction_free > 0.2, fraction_free  # filtering is not broken
    assert fraction_free < 0.99, fraction_free  # self-collision is detected
