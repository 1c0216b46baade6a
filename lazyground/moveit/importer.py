"""``import_moveit_file``: read a MoveIt planning scene, write a lazyground scene (#15).

The output is written to a temporary file beside it and renamed into place only after
it loads as a scene and its start is collision-free, so a failed import leaves nothing.
"""

from __future__ import annotations

import os
import re
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import yaml

from lazyground.moveit.convert import ImportOptions, ImportSummary, convert_moveit
from lazyground.moveit.scene_text import parse_scene_text
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
    """The parsed YAML of ``path`` (MoveIt's text ``.scene`` format read as the same mapping); XML and other
    non-YAML files say what they are.

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
    if kind is FileKind.SCENE_TEXT or path.suffix.lower() == ".scene":
        return parse_scene_text(text, str(path))
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
    mesh_dir = output.resolve().parent / f"{output.stem}_meshes"
    written = write_inline_meshes(data, mesh_dir, output)
    try:
        return _write_scene(data, path, output, options, check_start)
    except BaseException:  # nothing is left behind: the meshes written for it go too
        for f in written:
            f.unlink(missing_ok=True)
        if written and mesh_dir.is_dir() and not any(mesh_dir.iterdir()):
            mesh_dir.rmdir()
        raise


def _write_scene(data, path: Path, output: Path, options: ImportOptions, check_start: bool) -> ImportResult:
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


def write_inline_meshes(data, mesh_dir: Path, output: Path) -> list[Path]:
    """Each collision object's inline mesh (``vertices`` and ``triangles``: a ``.scene`` file's, or a message's
    without a ``resource``) written as an OBJ file in ``mesh_dir``, its entry given a ``file://`` resource.

    Returns:
        The files written (the caller removes them if the import fails).
    """
    world = data.get("world") if isinstance(data, dict) else None
    entries = world.get("collision_objects") if isinstance(world, dict) else None
    written = []
    for entry in entries if isinstance(entries, list) else []:
        meshes = entry.get("meshes") if isinstance(entry, dict) else None
        for k, mesh in enumerate(meshes if isinstance(meshes, list) else []):
            if not isinstance(mesh, dict) or mesh.get("resource") or not mesh.get("vertices") or not mesh.get("triangles"):
                continue
            vertices = [[v.get(a, 0.0) for a in "xyz"] if isinstance(v, dict) else v for v in mesh["vertices"]]
            triangles = [t.get("vertex_indices") if isinstance(t, dict) else t for t in mesh["triangles"]]
            oid = re.sub(r"[^A-Za-z0-9_.-]+", "_", str(entry.get("id", "object")))
            target = mesh_dir / f"{oid}_{k}.obj"
            lines = [f"# {entry.get('id')!s}: mesh {k} imported by `lazyground import-moveit` into {output.name}"]
            try:
                lines += [f"v {float(x):.9g} {float(y):.9g} {float(z):.9g}" for x, y, z in vertices]
                lines += [f"f {int(a) + 1} {int(b) + 1} {int(c) + 1}" for a, b, c in triangles]
            except (TypeError, ValueError):
                raise SceneError(f"{output}: collision object {entry.get('id')!r}: meshes[{k}]: malformed vertices "
                                 f"or triangles") from None
            try:
                mesh_dir.mkdir(exist_ok=True)
                target.write_text("\n".join(lines) + "\n")
            except OSError as exc:
                raise SceneError(f"{target}: cannot write: {exc.strerror or exc}") from None
            written.append(target)
            mesh["resource"] = f"file://{target}"
    return written


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
        check_types(scene)
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
