"""A serial kinematic chain read off a Drake plant, evaluated in batches with numpy.

Drake's ``CalcRelativeTransform`` and ``CalcJacobianSpatialVelocity`` cost tens
of microseconds per call from Python, one configuration at a time. Goal
sampling solves IK from many random starts; here the chain from the world to
an end-effector frame becomes a list of fixed transforms and joint axes, so the
pose and geometric Jacobian of B configurations come from a few batched matrix
products. The plant stays the reference: tests compare both at random
configurations.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from pydrake.multibody.tree import PrismaticJoint, RevoluteJoint, WeldJoint

REVOLUTE, PRISMATIC = 0, 1


@dataclass(frozen=True)
class Chain:
    """World -> frame E through joints 0..n-1 (root first).

    ``X_before[k]`` is the fixed transform from the child side of joint k-1 (the
    world for k = 0) to joint k's axis frame; ``X_after`` from the last joint to E.
    ``index[k]`` is joint k's coordinate in the plant's position vector.
    """

    X_before: np.ndarray  # (n, 4, 4)
    X_after: np.ndarray  # (4, 4)
    axes: np.ndarray  # (n, 3), unit, in the joint's own frame (the motion is about z after alignment)
    kinds: np.ndarray  # (n,) REVOLUTE or PRISMATIC
    index: np.ndarray  # (n,) plant position index

    @property
    def n(self) -> int:
        return len(self.kinds)

    def forward(self, q_chain: np.ndarray, jacobian: bool = False):
        """World poses X_WE (B, 4, 4) of B chain configurations (B, n); with ``jacobian``
        also the geometric Jacobians (B, 6, n), rows (angular; linear) in world.

        Every joint's frame is turned so that its axis is z (``chain_to_frame`` folds
        the turn into the fixed transforms): a joint's motion then rotates the first
        two columns of the orientation so far, or shifts along its third.
        """
        q = np.atleast_2d(q_chain)
        B = q.shape[0]
        # T: the top three rows of the pose so far, (B, 3, 4); T @ A for a constant 4x4 A is one
        # (3B, 4) product (numpy's stacked matmul is ~5x slower here), rotation and position at once
        T = np.empty((B, 3, 4))
        T[:] = self.X_before[0, :3, :] if self.n else np.eye(4)[:3]
        frames = np.empty((B, self.n, 3, 2))  # per joint: its axis and origin in world, the columns 2:4 of T
        turn = np.exp(-1j * q)  # R @ Rz(q) turns (column 0 + i column 1) by e^(-iq)
        for k in range(self.n):
            if k:
                T = (T.reshape(-1, 4) @ self.X_before[k]).reshape(B, 3, 4)
            frames[:, k] = T[:, :, 2:]
            if self.kinds[k] == PRISMATIC:
                T[:, :, 3] += T[:, :, 2] * q[:, k, None]
            else:  # columns 0 and 1 side by side in memory: one complex product turns both
                T.view(np.complex128)[:, :, 0] *= turn[:, k, None]
        T = (T.reshape(-1, 4) @ self.X_after).reshape(B, 3, 4)
        X = np.zeros((B, 4, 4))
        X[:, :3, :], X[:, 3, 3] = T, 1.0
        p = T[:, :, 3]
        if not jacobian:
            return X
        J = np.zeros((B, 6, self.n))
        rev = self.kinds == REVOLUTE
        a, r = frames[..., 0], p[:, None, :] - frames[..., 1]  # axis and lever of every joint, in world
        J[:, 0:3, rev] = a[:, rev].transpose(0, 2, 1)
        cross = np.stack([a[..., 1] * r[..., 2] - a[..., 2] * r[..., 1],
                          a[..., 2] * r[..., 0] - a[..., 0] * r[..., 2],
                          a[..., 0] * r[..., 1] - a[..., 1] * r[..., 0]], axis=1)
        J[:, 3:6] = np.where(rev, cross, a.transpose(0, 2, 1))
        return X, J


def _align_z(axis: np.ndarray) -> np.ndarray:
    """A rotation (4x4) whose z column is ``axis``."""
    z = axis / np.linalg.norm(axis)
    helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x)
    T = np.eye(4)
    T[:3, :3] = np.column_stack([x, np.cross(z, x), z])
    return T


def joints_to_world(plant, body) -> list:
    """The joints from ``body`` up to the world, nearest first (welds included).

    Raises:
        ValueError: a body on the way hangs on no joint.
    """
    out = []
    world = plant.world_body().index()
    while body.index() != world:
        joint = next((plant.get_joint(j) for j in plant.GetJointIndices() if plant.get_joint(j).child_body().index() == body.index()), None)
        if joint is None:
            raise ValueError(f"body {body.name()} is not connected to the world by joints")
        out.append(joint)
        body = joint.parent_body()
    return out


def chain_to_frame(plant, frame) -> Chain:
    """The chain from the world to ``frame`` (a plant Frame).

    Raises:
        ValueError: a joint on the way is neither revolute, prismatic nor welded
            (e.g. a floating or planar base), which this chain cannot express.
    """
    joints = joints_to_world(plant, frame.body())[::-1]  # root first
    X_before, axes, kinds, index = [], [], [], []
    pending = np.eye(4)  # fixed transforms since the last moving joint
    for joint in joints:
        X_PF = joint.frame_on_parent().GetFixedPoseInBodyFrame().GetAsMatrix4()
        X_MC = joint.frame_on_child().GetFixedPoseInBodyFrame().inverse().GetAsMatrix4()
        if isinstance(joint, WeldJoint):
            pending = pending @ X_PF @ joint.X_FM().GetAsMatrix4() @ X_MC
            continue
        if isinstance(joint, RevoluteJoint):
            kinds.append(REVOLUTE)
            axes.append(np.asarray(joint.revolute_axis(), float))
        elif isinstance(joint, PrismaticJoint):
            kinds.append(PRISMATIC)
            axes.append(np.asarray(joint.translation_axis(), float))
        else:
            raise ValueError(f"joint {joint.name()} ({joint.type_name()}) cannot be part of an IK chain")
        A = _align_z(axes[-1])  # the joint frame turned so its axis is z, and back after it
        X_before.append(pending @ X_PF @ A)
        index.append(joint.position_start())
        pending = A.T @ X_MC
    X_after = pending @ frame.GetFixedPoseInBodyFrame().GetAsMatrix4()
    return Chain(np.array(X_before).reshape(-1, 4, 4), X_after, np.array(axes).reshape(-1, 3),
                 np.array(kinds, int), np.array(index, int))
