"""Tests for the bundled primitive-geometry arms: models/panda (Franka Panda) and models/ur5e (UR5e).

Forward kinematics are checked against the manufacturers' published DH tables, computed here
independently of the URDF (Franka: Craig's modified DH; Universal Robots: standard DH), and
against poses worked out by hand.
"""

import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from pydrake.geometry import Role  # noqa: E402
from pydrake.multibody.parsing import Parser  # noqa: E402
from pydrake.planning import RobotDiagramBuilder, SceneGraphCollisionChecker  # noqa: E402

from lazyground.robots.defaults import defaults_for_model  # noqa: E402

MODELS = Path(__file__).resolve().parents[2] / "models"

# Franka's published modified-DH table (a_{i-1}, d_i, alpha_{i-1}) and the flange / hand / TCP offsets.
PANDA_MDH = [(0, 0.333, 0), (0, 0, -math.pi / 2), (0, 0.316, math.pi / 2), (0.0825, 0, math.pi / 2),
             (-0.0825, 0.384, -math.pi / 2), (0, 0, math.pi / 2), (0.088, 0, math.pi / 2)]
PANDA_FLANGE, PANDA_TCP = 0.107, 0.1034
# Universal Robots' published UR5e DH table (a_i, d_i, alpha_i).
UR5E_DH = [(0, 0.1625, math.pi / 2), (-0.425, 0, 0), (-0.3922, 0, 0), (0, 0.1333, math.pi / 2),
           (0, 0.0997, -math.pi / 2), (0, 0.0996, 0)]
UR5E_TCP = 0.125  # tool_tcp past tool0, along tool0's z


def _rz(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])


def _rx(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1]])


def _tr(x, y, z):
    T = np.eye(4)
    T[:3, 3] = (x, y, z)
    return T


def panda_reference(q):
    """TCP pose from the modified-DH table: T_i = Rx(alpha_{i-1}) Tx(a_{i-1}) Rz(q_i) Tz(d_i)."""
    T = np.eye(4)
    for (a, d, alpha), qi in zip(PANDA_MDH, q):
        T = T @ _rx(alpha) @ _tr(a, 0, 0) @ _rz(qi) @ _tr(0, 0, d)
    return T @ _tr(0, 0, PANDA_FLANGE) @ _rz(-math.pi / 4) @ _tr(0, 0, PANDA_TCP)


def ur5e_reference(q):
    """TCP pose from the standard DH table: T_i = Rz(q_i) Tz(d_i) Tx(a_i) Rx(alpha_i); ROS base_link
    is the DH base turned pi about z."""
    T = _rz(math.pi)
    for (a, d, alpha), qi in zip(UR5E_DH, q):
        T = T @ _rz(qi) @ _tr(0, 0, d) @ _tr(a, 0, 0) @ _rx(alpha)
    return T @ _tr(0, 0, UR5E_TCP)


ROBOTS = {
    "panda": dict(urdf=MODELS / "panda" / "panda.urdf", reference=panda_reference, dof=7),
    "ur5e": dict(urdf=MODELS / "ur5e" / "ur5e.urdf", reference=ur5e_reference, dof=6),
}


class Arm:
    def __init__(self, name):
        info = ROBOTS[name]
        self.defaults = defaults_for_model(info["urdf"])
        builder = RobotDiagramBuilder(time_step=0.0)
        self.plant = builder.plant()
        (self.instance,) = Parser(self.plant).AddModels(str(info["urdf"]))
        self.plant.WeldFrames(self.plant.world_frame(), self.plant.GetFrameByName(self.defaults.base_link))
        self.diagram = builder.Build()
        self.context = self.diagram.CreateDefaultContext()
        self.reference = info["reference"]
        self.dof = info["dof"]
        self.checker = SceneGraphCollisionChecker(
            model=self.diagram, robot_model_instances=[self.instance], edge_step_size=0.05,
            env_collision_padding=0.005, self_collision_padding=0.005)

    def q(self, pose_name):
        pose = self.defaults.named_poses[pose_name]
        return np.array([pose[j] for j in self.defaults.planned_joints])

    def tcp(self, q):
        pc = self.plant.GetMyContextFromRoot(self.context)
        self.plant.SetPositions(pc, np.asarray(q, float))
        frame = self.plant.GetFrameByName(self.defaults.end_effector.frame)
        return self.plant.CalcRelativeTransform(pc, self.plant.world_frame(), frame).GetAsMatrix4()

    def sample(self, rng, n):
        lo, hi = self.plant.GetPositionLowerLimits(), self.plant.GetPositionUpperLimits()
        return rng.uniform(lo, hi, size=(n, len(lo)))


@pytest.fixture(scope="module", params=sorted(ROBOTS))
def arm(request):
    return Arm(request.param)


def test_planned_joints_are_the_plant_positions_in_order(arm):
    assert arm.plant.num_positions() == arm.dof
    for index, name in enumerate(arm.defaults.planned_joints):
        joint = arm.plant.GetJointByName(name, arm.instance)
        assert joint.position_start() == index and joint.type_name() == "revolute"
        assert joint.velocity_upper_limits()[0] > 0  # URDF velocity limits are present


def test_fk_matches_published_dh_at_random_configurations(arm):
    for q in arm.sample(np.random.default_rng(7), 25):
        np.testing.assert_allclose(arm.tcp(q), arm.reference(q), atol=1e-9)


def test_panda_ready_pose_by_hand():
    arm = Arm("panda")
    T = arm.tcp(arm.q("ready"))
    # ready, in the x-z plane: joint 2 tilts the upper arm 45 deg back (0.316 to joint 3), the elbow
    # offset 0.0825 is perpendicular to it (45 deg forward-up); joint 4 at -135 deg turns the forearm
    # horizontal, its -0.0825 offset pointing straight up; forearm 0.384 forward; joint 6 at 90 deg
    # points the flange down with the 0.088 wrist offset forward; flange 0.107, TCP 0.1034 down.
    s = math.sqrt(0.5)
    x = -0.316 * s + 0.0825 * s + 0.384 + 0.088  # = 0.30689
    z = 0.333 + 0.316 * s + 0.0825 * s + 0.0825 - 0.107 - 0.1034  # = 0.48688
    np.testing.assert_allclose(T[:3, 3], [x, 0.0, z], atol=1e-4)
    np.testing.assert_allclose(T[:3, 2], [0, 0, -1], atol=1e-6)  # approach axis straight down
    np.testing.assert_allclose(T[:3, 1], [0, -1, 0], atol=1e-6)  # fingers close along world y


def test_ur5e_zero_and_ready_poses_by_hand():
    arm = Arm("ur5e")
    T = arm.tcp(np.zeros(6))
    # all zero: arm straight out along +x (-(a2 + a3)), wrist offsets d4 + d6 (+ the TCP) along +y, d1 - d5 up
    np.testing.assert_allclose(T[:3, 3], [0.425 + 0.3922, 0.1333 + 0.0996 + UR5E_TCP, 0.1625 - 0.0997], atol=1e-9)
    np.testing.assert_allclose(T[:3, 2], [0, 1, 0], atol=1e-9)
    T = arm.tcp(arm.q("ready"))
    # ready: upper arm straight up (0.425), forearm forward (0.3922) with the wrist offset d4 along +y,
    # wrist 1 turns the wrist down, d5 forward, and the tool (d6 + TCP) straight down
    np.testing.assert_allclose(T[:3, 3], [0.3922 + 0.0997, 0.1333, 0.1625 + 0.425 - 0.0996 - UR5E_TCP], atol=1e-6)
    np.testing.assert_allclose(T[:3, 2], [0, 0, -1], atol=1e-6)


def test_named_poses_are_collision_free_and_within_limits(arm):
    lo, hi = arm.plant.GetPositionLowerLimits(), arm.plant.GetPositionUpperLimits()
    for name in arm.defaults.named_poses:
        q = arm.q(name)
        assert np.all(q >= lo) and np.all(q <= hi), name
        assert arm.checker.CheckConfigCollisionFree(q), name


def test_tcp_sits_between_the_open_fingers_clear_of_the_palm(arm):
    ee = arm.defaults.end_effector
    T = arm.tcp(arm.q(arm.defaults.start))
    scene_graph = arm.diagram.scene_graph()
    query = scene_graph.get_query_output_port().Eval(scene_graph.GetMyContextFromRoot(arm.context))
    inspector = query.inspector()
    clearance = {}
    for r in query.ComputeSignedDistanceToPoint(T[:3, 3], threshold=0.3):
        body = arm.plant.GetBodyFromFrameId(inspector.GetFrameId(r.id_G)).name()
        clearance[body] = min(r.distance, clearance.get(body, 1.0))
    # the pads' inner faces are opening / 2 away along the closing axis; nothing is closer
    assert min(clearance.values()) == pytest.approx(ee.opening / 2, abs=1e-6)
    closing = T[:3, 1]
    for sign in (1, -1):  # moving along the closing axis by half the opening reaches a pad
        p = T[:3, 3] + sign * (ee.opening / 2 + 0.004) * closing
        assert min(r.distance for r in query.ComputeSignedDistanceToPoint(p, threshold=0.3)) < 0


def test_every_body_with_geometry_is_checked_and_self_collision_is_detected(arm):
    inspector = arm.diagram.scene_graph().model_inspector()
    with_geometry = [b for b in arm.plant.GetBodyIndices(arm.instance)
                     if inspector.NumGeometriesForFrameWithRole(arm.plant.GetBodyFrameIdOrThrow(b), Role.kProximity)]
    assert len(with_geometry) >= arm.dof + 2
    free = np.mean([arm.checker.CheckConfigCollisionFree(q) for q in arm.sample(np.random.default_rng(0), 200)])
    assert 0.3 < free < 0.99, free
