"""Issue #33: the pose regions' numbers in bulk (lazyground/regions/table.py and its helpers) are those of the
per-region computation they replaced, written out here, bit for bit (0.0 and -0.0 told apart)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from lazyground.geometry import Pose, matrix_to_rpy, pose_matrices, rpy_to_matrix
from lazyground.regions import ConfigRegion, PlacementRegion, WorkspaceRegion
from lazyground.regions.base import unit_maps
from lazyground.regions.learned import ANGLES, BIN_ANGLE, BIN_LENGTH, MAX_BINS, RegionLearner
from lazyground.regions.table import build_pose_table, pose_table


def _same_bits(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def _poses(rng, n):
    out = [Pose(), Pose((-0.0, 0.0, -0.0), (-0.0, math.pi, -math.pi / 2)), Pose((1, 2, 3), (0, 0, 0))]
    return out + [Pose(tuple(rng.uniform(-2, 2, 3)), tuple(rng.uniform(-4, 4, 3))) for _ in range(n)]


def _unit_map_one_by_one(region):
    """GoalRegion.unit_map as it was, one region at a time."""
    lo, hi = np.asarray(region.lower, float), np.asarray(region.upper, float)
    span = hi - lo
    for i in region.wrap:
        if span[i] < 0:
            span[i] += 2 * np.pi
    wrapped = np.zeros(len(lo), bool)
    wrapped[list(region.wrap)] = True
    return lo, span, wrapped


def _regions(rng, n, cls=WorkspaceRegion):
    """Grasp-like regions: a few templates (X_SE, approach, bounds) over many reference frames."""
    templates = [(Pose(), (-0.1, 0.0, 0.0), (0.01, 0, 0, -math.pi, 0, 0), (0.03, 0, 0, math.pi, 0, 0)),
                 (Pose((0.0, 0.0, 0.02), (0.0, -math.pi / 2, 0.0)), (-0.1, -0.0, 0.0), (0, 0, -0.01, 0, -0.5, 3.0), (0, 0, 0.01, 0, 0.5, -3.0)),
                 (Pose((-0.01, 0.0, 0.0)), (-0.08, 0.0, 0.0), (-0.01, 0, -0.05, 0, 0, -math.pi), (0.01, 0, 0.05, 0, 0, math.pi))]
    out = []
    for k, X_WR in enumerate(_poses(rng, n)):
        X_SE, approach, lower, upper = templates[k % len(templates)]
        out.append(cls(id=f"can{k}/t{k % 3}", interpretation="pick", object=f"can{k}", lower=lower, upper=upper, wrap=(3, 4, 5),
                       frame="gripper", X_WR=X_WR, X_SE=X_SE, approach=approach))
    return out


def test_pose_matrices_are_pose_matrix_bit_for_bit():
    poses = _poses(np.random.default_rng(0), 200)
    assert _same_bits(pose_matrices(poses), np.array([p.matrix() for p in poses]))
    assert pose_matrices([]).shape == (0, 4, 4)
    assert np.allclose(pose_matrices(poses[3:])[:, :3, :3], [rpy_to_matrix(p.rpy) for p in poses[3:]])


def test_unit_maps_are_unit_map_bit_for_bit():
    rng = np.random.default_rng(1)
    regions = _regions(rng, 30) + [ConfigRegion(id="c", interpretation="", object="", lower=(3.0, 0.0, -1.0, 0, 0, 0),
                                                upper=(-3.0, 1.0, 1.0, 0, 0, 0), wrap=(0, 1))]
    lower, span, wrapped = unit_maps(regions)
    for j, r in enumerate(regions):
        for bulk, one, single in zip((lower[j], span[j], wrapped[j]), _unit_map_one_by_one(r), r.unit_map()):
            assert _same_bits(bulk, one) and _same_bits(single, one)
    assert span[-1, 0] == pytest.approx(2 * np.pi - 6)


@pytest.mark.parametrize("placement", [False, True])
def test_pose_table_is_the_per_region_table(placement):
    """Row by row, what IKGoalSource's region table and the reach prior's keeps computed per region."""
    regions = _regions(np.random.default_rng(2), 40, PlacementRegion if placement else WorkspaceRegion)
    attached = SimpleNamespace(body="hand", X_BO=Pose((0.0, 0.01, 0.05), (0.1, -0.0, 0.3))) if placement else None
    table = build_pose_table(regions, attached)
    for j, r in enumerate(regions):
        frame, X_ET = r.robot_target(Pose(), attached)
        M_ET = X_ET.matrix()
        T = np.eye(4)
        T[:3, 3] = r.approach
        assert table.frames[j] == frame == ("hand" if placement else "gripper")
        assert _same_bits(table.X_WR[j], r.X_WR.matrix())
        assert _same_bits(table.X_ST[j], r.X_SE.matrix() @ M_ET)
        assert _same_bits(table.approach[j], (np.linalg.inv(M_ET) @ T @ M_ET)[:3, 3])
        for bulk, one in zip((table.lower[j], table.span[j], table.wrapped[j]), _unit_map_one_by_one(r)):
            assert _same_bits(bulk, one)
    assert not table.X_WR.flags.writeable


def test_pose_table_is_shared_by_the_same_tuple_only():
    regions = tuple(_regions(np.random.default_rng(3), 5))
    table = pose_table(regions, None)
    assert pose_table(regions, None) is table
    assert pose_table(tuple(regions), None) is table  # tuple() of a tuple is the tuple
    assert pose_table(tuple(list(regions)), None) is not table  # an equal tuple: built again, the same numbers
    assert _same_bits(pose_table(tuple(list(regions)), None).X_ST, table.X_ST)
    with pytest.raises(ValueError, match="attached"):
        pose_table(tuple(_regions(np.random.default_rng(3), 1, PlacementRegion)), None)


def test_learner_bins_are_the_per_region_bins():
    regions = _regions(np.random.default_rng(4), 30)
    learner = RegionLearner(unit_maps(regions), 0.5)
    for j, r in enumerate(regions):
        _, span, _ = _unit_map_one_by_one(r)
        n = [min(MAX_BINS, math.ceil(s / (BIN_ANGLE if i in ANGLES else BIN_LENGTH) - 1e-9)) for i, s in enumerate(span)]
        assert learner._bins[j] == {i: k for i, k in enumerate(n) if k > 1}


def _old_matrix(pose):
    """Pose.matrix as it was: np.eye, then the rotation and the translation assigned."""
    X = np.eye(4)
    X[:3, :3] = rpy_to_matrix(pose.rpy)
    X[:3, 3] = pose.xyz
    return X


def _old_rpy(R):
    """matrix_to_rpy as it was: numpy scalars into math."""
    pitch = math.atan2(-R[2, 0], math.hypot(R[0, 0], R[1, 0]))
    if abs(math.cos(pitch)) < 1e-9:
        return np.array([math.atan2(-R[1, 2], R[1, 1]), pitch, 0.0])
    return np.array([math.atan2(R[2, 1], R[2, 2]), pitch, math.atan2(R[1, 0], R[0, 0])])


def test_pose_matrix_and_from_matrix_are_the_old_numbers_bit_for_bit():
    rng = np.random.default_rng(5)
    poses = _poses(rng, 300) + [Pose((0, 1, 2), (0.3, math.pi / 2, 0.2)), Pose((0.5, -0.0, 0), (-0.0, -math.pi / 2, -0.0))]
    for p in poses:
        assert _same_bits(p.matrix(), _old_matrix(p))
    products = [_old_matrix(a) @ _old_matrix(b) for a, b in zip(poses, poses[1:])]
    for a, b, X in zip(poses, poses[1:], products):
        old = Pose(tuple(float(v) for v in X[:3, 3]), tuple(float(v) for v in _old_rpy(X[:3, :3])))
        for got in (Pose.from_matrix(X), a.compose(b)):
            assert _same_bits(got.xyz, old.xyz) and _same_bits(got.rpy, old.rpy)
            assert all(type(v) is float for v in got.xyz + got.rpy)
        assert _same_bits(matrix_to_rpy(X[:3, :3]), _old_rpy(X[:3, :3]))
    for p in poses[-2:]:  # gimbal lock
        X = _old_matrix(p)
        assert _same_bits(matrix_to_rpy(X[:3, :3]), _old_rpy(X[:3, :3])) and Pose.from_matrix(X).rpy[2] == 0.0
    X32 = _old_matrix(poses[5]).astype(np.float32)
    assert _same_bits(matrix_to_rpy(X32[:3, :3]), _old_rpy(X32[:3, :3]))
