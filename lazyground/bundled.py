"""The bundled scenes and robot models, found from any working directory.

``yaml_scenes/`` and ``models/`` live at the top of the source tree; the package
reaches them through ``lazyground/data/`` (symlinks in the source tree, copied
files in a wheel: ``pip install .`` ships them as package data), so a bare scene
name such as ``parking_1`` works wherever the command runs.
"""

from __future__ import annotations

from pathlib import Path

DATA = Path(__file__).resolve().parent / "data"
SOURCE_ROOT = Path(__file__).resolve().parents[1]


def data_dir(name: str) -> Path:
    """``DATA/name`` when present (installed or source tree), else ``SOURCE_ROOT/name``."""
    packaged = DATA / name
    return packaged if packaged.is_dir() else SOURCE_ROOT / name


def scene_names() -> list[str]:
    """Names of the bundled scenes (``parking_1``, ``fetch_cans_1``, ...)."""
    return sorted(p.stem for p in data_dir("yaml_scenes").glob("*.yaml"))


def bundled_scene(name: str) -> Path | None:
    """The bundled scene file a bare name means (``parking_1`` or ``parking_1.yaml``), or None.

    Only names without a folder part qualify: a path the user typed is never redirected.
    """
    if not name or Path(name).name != name:
        return None
    path = data_dir("yaml_scenes") / (name if name.endswith((".yaml", ".yml")) else f"{name}.yaml")
    return path if path.is_file() else None
