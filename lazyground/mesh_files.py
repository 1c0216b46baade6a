"""Mesh files without pydrake: read STL (binary or ASCII), write OBJ text, and sniff a
file's format (#15). Drake loads OBJ (and glTF/VTK) itself; an STL is handed to it as
an in-memory OBJ. Collision uses the mesh's convex hull either way (Drake's rule for
``Mesh`` proximity geometry), so a non-convex mesh fills its own hollows.
"""

from __future__ import annotations

import struct
from pathlib import Path

import numpy as np


class MeshFileError(ValueError):
    """A mesh file that cannot be read (the message is one line)."""


def read_stl(path: str | Path) -> tuple[np.ndarray, np.ndarray]:
    """An STL file's (vertices (n, 3), triangles (m, 3) indices), vertices merged.

    Raises:
        MeshFileError: not a readable STL file.
    """
    data = Path(path).read_bytes()
    if len(data) >= 84:
        (count,) = struct.unpack_from("<I", data, 80)
        if count > 0 and len(data) == 84 + 50 * count:  # binary: the size is exact
            rec = np.frombuffer(data, dtype=np.dtype([("n", "<3f4"), ("v", "<9f4"), ("a", "<u2")]), count=count, offset=84)
            return mesh_from_triangles(rec["v"].reshape(-1, 3, 3).astype(float))
    text = data.decode("ascii", errors="replace")
    if not text.lstrip().lower().startswith("solid"):
        raise MeshFileError(f"{path}: not an STL file (neither binary nor ASCII 'solid')")
    rows = [line.split()[1:4] for line in text.splitlines() if line.strip().lower().startswith("vertex")]
    try:
        points = np.array(rows, dtype=float)
    except ValueError:
        raise MeshFileError(f"{path}: malformed ASCII STL vertex line") from None
    if len(points) == 0 or len(points) % 3:
        raise MeshFileError(f"{path}: ASCII STL has {len(points)} vertices, not whole triangles")
    return mesh_from_triangles(points.reshape(-1, 3, 3))


def mesh_from_triangles(triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(vertices, triangle indices) of a triangle soup (n, 3, 3), vertices merged where they coincide exactly."""
    vertices, inverse = np.unique(np.asarray(triangles, float).reshape(-1, 3), axis=0, return_inverse=True)
    return vertices, inverse.reshape(-1, 3)


def obj_text(vertices: np.ndarray, triangles: np.ndarray) -> str:
    """An OBJ file's text for these vertices and triangles (1-based indices)."""
    lines = [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in triangles]
    return "\n".join(lines) + "\n"
