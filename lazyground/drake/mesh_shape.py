"""A scene's mesh geometry as a Drake shape (#15): OBJ as a file, STL converted to an
in-memory OBJ (lazyground.mesh_files). Drake collides with the mesh's convex hull."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from pydrake.common import MemoryFile
from pydrake.geometry import InMemoryMesh, Mesh

from lazyground.mesh_files import MeshFileError, obj_text, read_stl
from lazyground.scene.schema import MeshFile
from lazyground.typed_yaml import SceneError


def mesh_shape(mesh: MeshFile) -> Mesh:
    """The Drake Mesh for a scene mesh (scaled per axis).

    Raises:
        SceneError: the file cannot be read.
    """
    path = Path(mesh.file)
    scale = np.asarray(mesh.scale, float)
    if path.suffix.lower() == ".stl":
        try:
            text = obj_text(*read_stl(path))
        except (OSError, MeshFileError) as exc:
            raise SceneError(f"{path}: cannot read mesh: {exc}") from None
        return Mesh(InMemoryMesh(mesh_file=MemoryFile(text, ".obj", str(path))), scale)
    return Mesh(str(path), scale)
