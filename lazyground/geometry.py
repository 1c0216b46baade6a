"""Rigid-transform helpers in plain numpy (no pydrake), Drake monogram style.

A pose is stored as ``(xyz, rpy)``: translation in metres and extrinsic
roll-pitch-yaw in radians, ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)`` — the same
convention as Drake's ``RollPitchYaw`` and URDF.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np


def rpy_to_matrix(rpy) -> np.ndarray:
    """Rotation matrix of extrinsic roll-pitch-yaw angles."""
    return np.array(_rotation_rows(rpy))


def _rotation_rows(rpy) -> list[list[float]]:
    """:func:`rpy_to_matrix`'s rows as Python floats (a pose's matrix is built from them in one array)."""
    r, p, y = (float(a) for a in rpy)
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]


def rpy_to_matrices(rpy: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) of rows (N, 3) of extrinsic roll-pitch-yaw angles (:func:`rpy_to_matrix` for many)."""
    return _rotations(np.cos(rpy).T, np.sin(rpy).T)


def pose_matrices(poses) -> np.ndarray:
    """:meth:`Pose.matrix` of each of ``poses``, stacked (N, 4, 4), bit for bit: the sines and cosines by
    :mod:`math` as :func:`rpy_to_matrix` takes them, the products in its order (#33: ~20 µs a pose one by one)."""
    rpy = [float(a) for p in poses for a in p.rpy]
    c = np.fromiter(map(math.cos, rpy), float, len(rpy)).reshape(-1, 3).T
    s = np.fromiter(map(math.sin, rpy), float, len(rpy)).reshape(-1, 3).T
    X = np.zeros((c.shape[1], 4, 4))
    X[:, :3, :3] = _rotations(c, s)
    X[:, :3, 3] = np.fromiter(itertools.chain.from_iterable(p.xyz for p in poses), float, 3 * len(X)).reshape(-1, 3)
    X[:, 3, 3] = 1.0
    return X


def _rotations(c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """The rotation matrices (N, 3, 3) of cosines ``c`` and sines ``s`` (3, N) of (roll, pitch, yaw)."""
    (cr, cp, cy), (sr, sp, sy) = c, s
    R = np.empty((c.shape[1], 3, 3))
    R[:, 0, 0], R[:, 0, 1], R[:, 0, 2] = cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr
    R[:, 1, 0], R[:, 1, 1], R[:, 1, 2] = sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr
    R[:, 2, 0], R[:, 2, 1], R[:, 2, 2] = -sp, cp * sr, cp * cr
    return R


def matrix_to_rpy(R: np.ndarray) -> np.ndarray:
    """Roll-pitch-yaw of a rotation matrix (pitch in [-pi/2, pi/2])."""
    return np.array(_rpy_of_rows(np.asarray(R).tolist()))


def _rpy_of_rows(R: list[list[float]]) -> tuple[float, float, float]:
    """:func:`matrix_to_rpy` of a matrix's rows as Python floats (the first three rows and columns are read)."""
    pitch = math.atan2(-R[2][0], math.hypot(R[0][0], R[1][0]))
    if abs(math.cos(pitch)) < 1e-9:  # gimbal lock: fold yaw into roll
        return math.atan2(-R[1][2], R[1][1]), pitch, 0.0
    return math.atan2(R[2][1], R[2][2]), pitch, math.atan2(R[1][0], R[0][0])


def quaternion_xyzw_to_matrix(q) -> np.ndarray:
    """Rotation matrix of a unit quaternion given as (x, y, z, w)."""
    x, y, z, w = (float(a) for a in q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def wrap_angle(a):
    """Wrap angles to [-pi, pi)."""
    return (np.asarray(a) + np.pi) % (2 * np.pi) - np.pi


@dataclass(frozen=True)
class Pose:
    """A rigid transform X_AB: frame B measured and expressed in frame A."""

    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rpy: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @staticmethod
    def from_matrix(X: np.ndarray) -> "Pose":
        rows = np.asarray(X).tolist()  # (Python floats: ~3x cheaper than numpy's scalars here, the same numbers)
        return Pose((float(rows[0][3]), float(rows[1][3]), float(rows[2][3])), _rpy_of_rows(rows))

    def matrix(self) -> np.ndarray:
        (r0, r1, r2), (x, y, z) = _rotation_rows(self.rpy), (float(v) for v in self.xyz)
        return np.array([r0 + [x], r1 + [y], r2 + [z], [0.0, 0.0, 0.0, 1.0]])

    def rotation(self) -> np.ndarray:
        return rpy_to_matrix(self.rpy)

    def compose(self, other: "Pose") -> "Pose":
        """X_AC = X_AB · X_BC."""
        return Pose.from_matrix(self.matrix() @ other.matrix())

    def inverse(self) -> "Pose":
        return Pose.from_matrix(np.linalg.inv(self.matrix()))

    def transform_points(self, p_B: np.ndarray) -> np.ndarray:
        """Points measured in B, returned in A (rows are points)."""
        p_B = np.atleast_2d(p_B)
        return p_B @ self.rotation().T + np.asarray(self.xyz)

    def to_json(self) -> dict:
        return {"xyz": [round(v, 9) for v in self.xyz], "rpy": [round(v, 9) for v in self.rpy]}
