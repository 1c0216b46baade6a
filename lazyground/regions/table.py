"""A request's pose regions as stacked arrays, built once and shared by the reach prior and the IK source.

A 64-can rack grounds ~256 pose regions; taking each region's matrices and bounds one at a time cost
~20 ms a request, twice over (the reach prior's keeps, the IK source's region table; #33). Here every
region's reference frame is one bulk :func:`~lazyground.geometry.pose_matrices`, the bounds one
:func:`~lazyground.regions.base.unit_maps`, and what depends only on a region's template and the robot
(X_ST, the approach) is computed once per distinct template. The numbers are those of the per-region
computation bit for bit.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

import numpy as np

from lazyground.geometry import Pose, pose_matrices
from lazyground.regions.base import unit_maps

RECENT = 4  # tables kept by the identity of their regions tuple (one request's reach prior and IK source share one)
_RECENT: list[tuple] = []  # (regions, attached, table), newest first: holding them keeps the identities valid
_IDENTITY = Pose()


@dataclass(frozen=True, eq=False)
class PoseTable:
    """Row j: region j's robot frame, X_WR, X_ST = X_SE · X_ET, its approach in the robot frame's axes
    (X_ET^-1 · T(approach) · X_ET, translation), and its unit map (lower, span, wrapped). Read only."""

    frames: tuple[str, ...]
    X_WR: np.ndarray  # (N, 4, 4)
    X_ST: np.ndarray  # (N, 4, 4)
    approach: np.ndarray  # (N, 3)
    lower: np.ndarray  # (N, 6)
    span: np.ndarray  # (N, 6)
    wrapped: np.ndarray  # (N, 6) bool


def pose_table(regions: tuple, attached) -> PoseTable:
    """The :class:`PoseTable` of pose regions ``regions`` for a robot carrying ``attached`` (None: nothing), the
    same one for the same tuple and attachment among the last RECENT asked.

    Raises:
        ValueError: a placement region without a carried object (:meth:`PoseRegion.robot_target`).
    """
    for entry in _RECENT:
        if entry[0] is regions and entry[1] is attached:
            return entry[2]
    table = build_pose_table(regions, attached)
    _RECENT.insert(0, (regions, attached, table))
    del _RECENT[RECENT:]
    return table


def build_pose_table(regions, attached) -> PoseTable:
    """:func:`pose_table` without the sharing."""
    targets = [r.robot_target(_IDENTITY, attached) for r in regions]
    # X_ST and the approach depend on a region's X_SE, approach and X_ET only: once per distinct set of bits
    # (0.0 and -0.0 kept apart, as they may differ in the result)
    templates: dict[bytes, int] = {}
    rows = [templates.setdefault(struct.pack("15d", *r.X_SE.xyz, *r.X_SE.rpy, *X_ET.xyz, *X_ET.rpy, *r.approach), len(templates))
            for r, (_, X_ET) in zip(regions, targets)]
    firsts = {k: j for j, k in reversed(list(enumerate(rows)))}  # template -> its first region
    X_ST, approach = np.zeros((len(templates), 4, 4)), np.zeros((len(templates), 3))
    for k, j in firsts.items():
        X_ST[k], approach[k] = _template(regions[j].X_SE, targets[j][1], regions[j].approach)
    arrays = (pose_matrices([r.X_WR for r in regions]).reshape(len(regions), 4, 4), X_ST[rows].reshape(len(regions), 4, 4),
              approach[rows].reshape(len(regions), 3), *unit_maps(regions))
    for a in arrays:
        a.flags.writeable = False  # shared by the table's users
    return PoseTable(tuple(t[0] for t in targets), *arrays)


def _template(X_SE: Pose, X_ET: Pose, approach) -> tuple[np.ndarray, np.ndarray]:
    """(X_SE · X_ET, the approach in the robot frame's axes: X_ET^-1 · T(approach) · X_ET's translation)."""
    M_ET = X_ET.matrix()
    T = np.eye(4)
    T[:3, 3] = approach
    return X_SE.matrix() @ M_ET, (np.linalg.inv(M_ET) @ T @ M_ET)[:3, 3]
