"""Mesh references of a MoveIt scene (#15): find the file, check it can be read.

A ``resource`` is ``package://NAME/rest`` (found through ``--package NAME=DIR``),
``file:///abs``, an absolute path or a path relative to the scene file. OBJ and STL
are imported (Drake collides with the convex hull); other formats (DAE, ...) and
missing files are dropped, counted in one warning.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lazyground.mesh_files import MeshFileError, read_stl
from lazyground.scene.schema import MESH_SUFFIXES
from lazyground.typed_yaml import SceneError


@dataclass(frozen=True)
class MeshLookup:
    """Where mesh resources are looked for."""

    scene_dir: Path
    packages: dict[str, Path]


@dataclass
class MeshTally:
    """Meshes imported and dropped during one import (with why each was dropped)."""

    imported: int = 0
    reasons: list[str] = field(default_factory=list)

    @property
    def dropped(self) -> int:
        return len(self.reasons)

    def drop(self, reason: str) -> None:
        self.reasons.append(reason)


def find_mesh(resource: str, lookup: MeshLookup) -> tuple[Path | None, str]:
    """(the mesh file, or None with the reason it was dropped)."""
    if resource.startswith("package://"):
        package, _, rest = resource[len("package://"):].partition("/")
        if package not in lookup.packages:
            return None, f"package {package!r} not given (--package {package}=DIR)"
        path = lookup.packages[package] / rest
    elif resource.startswith("file://"):
        path = Path(resource[len("file://"):])
    else:
        path = Path(resource)
        path = path if path.is_absolute() else lookup.scene_dir / path
    if not path.is_file():
        return None, f"{path} not found"
    if path.suffix.lower() not in MESH_SUFFIXES:
        return None, f"{path.suffix} files are not imported (OBJ, STL; convert it)"
    if path.suffix.lower() == ".stl":
        try:
            read_stl(path)
        except (OSError, MeshFileError) as exc:
            return None, str(exc)
    return path.resolve(), ""
