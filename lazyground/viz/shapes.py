"""Meshcat shapes that pydrake does not offer directly."""

from __future__ import annotations

import numpy as np
from pydrake.geometry import Cylinder, Meshcat, Rgba
from pydrake.math import RigidTransform, RotationMatrix


def draw_tube(meshcat: Meshcat, path: str, points: np.ndarray, radius: float, rgba: Rgba) -> None:
    """A polyline through ``points`` (3, n) as cylinders of ``radius``: visible at any zoom, unlike a WebGL line."""
    for i in range(points.shape[1] - 1):
        a, b = points[:, i], points[:, i + 1]
        d = b - a
        length = float(np.linalg.norm(d))
        if length < 1e-9:
            continue
        z = d / length  # the cylinder's axis is its frame's z
        helper = np.array([1.0, 0.0, 0.0]) if abs(z[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        x = np.cross(helper, z)
        x /= np.linalg.norm(x)
        R = RotationMatrix(np.column_stack([x, np.cross(z, x), z]))
        name = f"{path}/{i}"
        meshcat.SetObject(name, Cylinder(radius, length), rgba)
        meshcat.SetTransform(name, RigidTransform(R, (a + b) / 2))
