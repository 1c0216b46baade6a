"""Serial kinematic chains and body trees read off a Drake plant, evaluated in batches with numpy.

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
        a, r = frames[..., 0], p[:, None, :] - frames[..., 1]  # axis and lever of every joint, in world
        (ax, ay, az), (rx, ry, rz) = a.transpose(2, 0, 1), r.transpose(2, 0, 1)
        J = np.empty((B, 6, self.n))
        J[:, 0], J[:, 1], J[:, 2] = ax, ay, az  # row by row: a stacked cross product costs more here
        J[:, 3], J[:, 4], J[:, 5] = ay * rz - az * ry, az * rx - ax * rz, ax * ry - ay * rx
        prismatic = self.kinds == PRISMATIC
        if prismatic.any():  # no rotation; the translation along the axis
            J[:, 0:3, prismatic] = 0.0
            J[:, 3:6, prismatic] = a[:, prismatic].transpose(0, 2, 1)
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


def _joint_parts(joint):
    """(kind, axis, X_PF @ A, A.T @ X_MC) of a revolute or prismatic joint, A turning its axis onto z;
    (None, None, X_PC, None) of a weld.

    Raises:
        ValueError: the joint is neither revolute, prismatic nor welded (e.g. a floating or planar base).
    """
    X_PF = joint.frame_on_parent().GetFixedPoseInBodyFrame().GetAsMatrix4()
    X_MC = joint.frame_on_child().GetFixedPoseInBodyFrame().inverse().GetAsMatrix4()
    if isinstance(joint, WeldJoint):
        return None, None, X_PF @ joint.X_FM().GetAsMatrix4() @ X_MC, None
    if isinstance(joint, RevoluteJoint):
        kind, axis = REVOLUTE, np.asarray(joint.revolute_axis(), float)
    elif isinstance(joint, PrismaticJoint):
        kind, axis = PRISMATIC, np.asarray(joint.translation_axis(), float)
    else:
        raise ValueError(f"joint {joint.name()} ({joint.type_name()}) cannot be part of a kinematic chain")
    A = _align_z(axis)  # the joint frame turned so its axis is z, and back after it
    return kind, axis, X_PF @ A, A.T @ X_MC


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
        kind, axis, X_pre, X_post = _joint_parts(joint)
        if kind is None:
            pending = pending @ X_pre
            continue
        kinds.append(kind)
        axes.append(axis)
        X_before.append(pending @ X_pre)
        index.append(joint.position_start())
        pending = X_post
    X_after = pending @ frame.GetFixedPoseInBodyFrame().GetAsMatrix4()
    return Chain(np.array(X_before).reshape(-1, 4, 4), X_after, np.array(axes).reshape(-1, 3),
                 np.array(kinds, int), np.array(index, int))


@dataclass(frozen=True)
class BodyTree:
    """World poses of several bodies at once, each moving joint computed once.

    The tree is kept per moving joint ("slot" s >= 1; slot 0 is the world): the frame
    of slot s is its joint's moving frame, ``K[s - 1]`` after slot ``parent[s - 1]``'s
    frame, then turned about (or shifted along) z by q[index[s - 1]]. Welds fold
    into constants: body k sits at ``F[k]`` in the frame of slot ``slot[k]``.
    """

    bodies: tuple  # BodyIndex per node
    parent: np.ndarray  # (m,) slot of the frame each moving joint hangs from
    K: np.ndarray  # (m, 4, 4)
    kinds: np.ndarray  # (m,) REVOLUTE or PRISMATIC
    index: np.ndarray  # (m,) plant position index
    slot: np.ndarray  # (n,) per body
    F: np.ndarray  # (n, 4, 4) per body

    def forward(self, q_full: np.ndarray, joints: bool = False) -> tuple[np.ndarray, ...]:
        """Rotations R_WB (B, n, 3, 3) and positions p_WB (B, n, 3) of every body at B plant position vectors;
        with ``joints``, then each moving joint's frame too: its axis (z) (B, m, 3) and origin (B, m, 3)."""
        q = np.atleast_2d(q_full)
        B, m = q.shape[0], len(self.kinds)
        R, p = [np.broadcast_to(np.eye(3), (B, 3, 3))], [np.zeros((B, 3))]  # per slot, contiguous
        qs = q[:, self.index]
        c, s = np.cos(qs), np.sin(qs)
        for j in range(m):
            Rp = R[self.parent[j]].reshape(-1, 3)  # R @ A for a constant A as one (3B, 3) product
            pj = p[self.parent[j]] + (Rp @ self.K[j, :3, 3]).reshape(B, 3)
            Rj = (Rp @ self.K[j, :3, :3]).reshape(B, 3, 3)
            if self.kinds[j] == PRISMATIC:
                pj += Rj[:, :, 2] * qs[:, j, None]
            else:  # Rj @ Rz(q): turn the first two columns
                cj, sj, x = c[:, j, None], s[:, j, None], Rj[:, :, 0].copy()
                Rj[:, :, 0] = x * cj + Rj[:, :, 1] * sj
                Rj[:, :, 1] = Rj[:, :, 1] * cj - x * sj
            R.append(Rj)
            p.append(pj)
        R_out, p_out = np.empty((B, len(self.slot), 3, 3)), np.empty((B, len(self.slot), 3))
        for k, j in enumerate(self.slot):
            Rj = R[j].reshape(-1, 3)
            R_out[:, k] = (Rj @ self.F[k, :3, :3]).reshape(B, 3, 3)
            p_out[:, k] = p[j] + (Rj @ self.F[k, :3, 3]).reshape(B, 3)
        if not joints:
            return R_out, p_out
        if not m:
            return R_out, p_out, np.zeros((B, 0, 3)), np.zeros((B, 0, 3))
        return R_out, p_out, np.stack([Rj[:, :, 2] for Rj in R[1:]], axis=1), np.stack(p[1:], axis=1)

    @property
    def fixed(self) -> np.ndarray:
        """Per body: whether only welds lie between it and the world (its pose never changes)."""
        return self.slot == 0


def body_tree(plant, bodies) -> BodyTree:
    """The tree of ``bodies`` (plant Bodies) and every body between them and the world.

    Raises:
        ValueError: a joint on the way is neither revolute, prismatic nor welded.
    """
    world = plant.world_body().index()
    where = {world: (0, np.eye(4))}  # BodyIndex -> (slot, F)
    order, parent, K, kinds, index = [], [], [], [], []
    for body in bodies:
        for joint in joints_to_world(plant, body)[::-1]:
            child = joint.child_body().index()
            if child in where:
                continue
            slot, F = where[joint.parent_body().index()]
            kind, _, X_pre, X_post = _joint_parts(joint)
            if kind is None:
                where[child] = (slot, F @ X_pre)
            else:
                parent.append(slot)
                K.append(F @ X_pre)
                kinds.append(kind)
                index.append(joint.position_start())
                where[child] = (len(kinds), X_post)
            order.append(child)
    return BodyTree(tuple(order), np.array(parent, int), np.array(K).reshape(-1, 4, 4), np.array(kinds, int),
                    np.array(index, int), np.array([where[b][0] for b in order], int),
                    np.array([where[b][1] for b in order]).reshape(-1, 4, 4))
