"""``import_moveit_file``: read a MoveIt planning scene, write a lazyground scene (#15).

The output is written to a temporary file beside it and renamed into place only after
it loads as a scene and its start is collision-free, so a failed import leaves nothing.
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import yaml

from lazyground.moveit.convert import ImportOptions, ImportSummary, convert_moveit
from lazyground.scene.file_kind import FileKind, kind_of_text, not_a_scene_message
from lazyground.scene.loader import load_scene
from lazyground.typed_yaml import SceneError, load_yaml


@dataclass(frozen=True)
class ImportResult:
    """A written scene: the summary and the planner it will run (the robot's defaults)."""

    output: Path
    summary: ImportSummary
    planner: str  # e.g. "bidirectional, step 0.5, edge checks every 0.05 (fetch robot.yaml)"


def read_moveit_yaml(path: Path):
    """The parsed YAML of ``path``; XML and other non-YAML files say what they are.

    Raises:
        SceneError: unreadable, not YAML, or not a planning scene (one line).
    """
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise SceneError(f"{path}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise SceneError(f"{path}: not a UTF-8 text file (a binary file? expected a MoveIt planning scene in YAML)") from None
    kind = kind_of_text(text)
    if kind is not FileKind.OTHER:
        raise SceneError(f"{path}: {not_a_scene_message(kind)}")
    try:
        return load_yaml(text)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}" if mark else ""
        raise SceneError(f"{path}: YAML syntax error{where}: {getattr(exc, 'problem', None) or 'invalid YAML'}") from None


def import_moveit_file(path, output, options: ImportOptions = ImportOptions(), check_start: bool = True) -> ImportResult:
    """Convert a MoveIt planning-scene YAML file into a lazyground scene file.

    Args:
        path: the MoveIt planning scene (``.yml``/``.yaml``).
        output: the scene file to write (nothing is left there on failure).
        options: robot, type rules, mesh packages, start options (the scene name defaults to the output's stem).
        check_start: build the Drake world and reject a start in collision (needs pydrake).

    Returns:
        The output path, the import summary and the planner the scene will run.

    Raises:
        SceneError: unreadable or malformed input (naming the source object), not a
            planning scene, or a start in collision (naming the pairs and the free named poses).
    """
    path, output = Path(path), Path(output)
    data = read_moveit_yaml(path)
    if options.name == ImportOptions().name:
        options = replace(options, name=output.stem)
    scene, summary = convert_moveit(data, str(path), options, scene_dir=path.parent)
    _relative_meshes(scene, output.resolve().parent)
    header = f"# Imported from {path.name} by `lazyground import-moveit`; no planner block: the robot's robot.yaml settings apply.\n"
    text = header + yaml.safe_dump(scene, sort_keys=False, default_flow_style=None, width=120)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{output.name}.", suffix=".tmp", dir=output.parent if str(output.parent) else ".")
    except OSError as exc:
        raise SceneError(f"{output}: cannot write: {exc.strerror or exc}") from None
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text)
        try:
            loaded = load_scene(tmp)
        except SceneError as exc:  # name the output, not the temporary file
            raise SceneError(str(exc).replace(tmp, str(output))) from None
        _check_types(loaded, path)
        if check_start:
            _check_start(loaded, summary.start_source, path)
        os.replace(tmp, output)
    except OSError as exc:
        raise SceneError(f"{output}: cannot write: {exc.strerror or exc}") from None
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    p = loaded.planner
    planner = (f"{p.algorithm}, step {p.step_size:g}, edge checks every {p.edge_resolution or p.step_size / 10:g}, "
               f"padding {p.collision_padding:g} (the {options.robot} robot.yaml's planner settings)")
    return ImportResult(output, summary, planner)


def _relative_meshes(scene: dict, base: Path) -> None:
    """Mesh paths inside the output's folder are written relative to it (the pair can move together)."""
    for item in scene["obstacles"]:
        mesh = item["geometry"].get("mesh")
        if mesh is not None and Path(mesh["file"]).is_relative_to(base):
            mesh["file"] = str(Path(mesh["file"]).relative_to(base))


def _check_types(scene, source: Path) -> None:
    """A --type rule may name a type the grounding does not know: say so now, not at the first plan."""
    from grounding.model import GroundingError
    from grounding.regions import check_types

    try:
        check_types(scene, source="")
    except GroundingError as exc:
        raise SceneError(f"{source}: {str(exc).split(' (types:')[0]} (from a --type or --rules rule; the types are "
                         f"those of lazyground/scene/types.yaml, or 'obstacle')") from None


def _check_start(scene, start_source: str, source: Path) -> None:
    try:
        from lazyground.drake.start_check import start_collision_message
    except ImportError:  # no pydrake: the planner reports invalid_start later
        return
    message = start_collision_message(scene, start_source)
    if message:
        raise SceneError(f"{source}: {message}")
