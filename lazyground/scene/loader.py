"""``load_scene(path) -> Scene``: read a scene YAML file strictly."""

from __future__ import annotations

import os
from collections import OrderedDict
from dataclasses import replace
from pathlib import Path

import numpy as np
import yaml

from lazyground.bundled import bundled_scene, data_dir, scene_names
from lazyground.robots.complete import complete_robot
from lazyground.scene.file_kind import FileKind, kind_of_mapping, kind_of_text
from lazyground.scene.robot_fill import fill_from_robot_defaults
from lazyground.scene.schema import Scene, SceneObject
from lazyground.typed_yaml import SceneError, line_of, load_dataclass, load_yaml

MAX_SCENE_BYTES = 5 * 1024 * 1024
SCENE_CACHE_SIZE = 8  # scene files kept parsed per process (api.plan on a path loads its file every call)
_SCENES: "OrderedDict[tuple, Scene]" = OrderedDict()
REPO_ROOT = Path(__file__).resolve().parents[2]


def models_dirs() -> list[Path]:
    """Where bundled model names are looked up: $LAZYGROUND_MODELS, then the repo's models/."""
    dirs = [Path(p) for p in os.environ.get("LAZYGROUND_MODELS", "").split(os.pathsep) if p]
    return dirs + [data_dir("models")]


def resolve_model(model: str, scene_dir: Path | None) -> Path | None:
    """A model file from a bundled name (``fetch`` → models/fetch/fetch.urdf) or a path."""
    candidates = []
    if scene_dir is not None:
        candidates.append(scene_dir / model)
    for d in models_dirs():
        candidates += [d / model, d / model / f"{model}.urdf", d / model / f"{model}.sdf"]
    candidates.append(REPO_ROOT / model)
    for c in candidates:
        if c.is_file():
            return c.resolve()
    return None


def parse_scene(text: str, source: str = "<string>", scene_dir: Path | None = None, robot_overrides: dict | None = None) -> Scene:
    """Parse scene YAML text; errors are SceneError with one line naming ``source``.

    ``robot_overrides`` replaces robot keys before the robot's defaults are filled in (the CLI's
    ``--package``/``--srdf``: absolute paths)."""
    problem = _not_a_scene(text)
    if problem:
        raise SceneError(f"{source}: {problem}")
    try:
        data = load_yaml(text)
    except RecursionError:  # PyYAML composes nested collections recursively
        raise SceneError(f"{source}: YAML nesting too deep") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        raise SceneError(f"{source}: YAML syntax error{where}: {problem}") from None
    if data is None:
        raise SceneError(f"{source}: the scene is empty")
    problem = _not_a_scene(text, data) if isinstance(data, dict) else None
    if problem:
        raise SceneError(f"{source}: {problem}")
    try:
        data = fill_from_robot_defaults(data, lambda model: resolve_model(model, scene_dir))
        scene = load_dataclass(data, Scene, "")
    except SceneError as exc:
        line = line_of(text, str(exc).split(": ", 1)[0])  # where the bad key is
        raise SceneError(f"{source}: {exc}" + (f" (line {line})" if line else "")) from None
    model = resolve_model(scene.robot.model, scene_dir)
    if model is None:
        raise SceneError(f"{source}: robot.model: model file {scene.robot.model!r} not found (bundled: {_bundled()})")
    problem = _overlap_problem(scene) or _mesh_problem(scene, scene_dir)
    if problem:
        raise SceneError(f"{source}: {problem}")
    # imported here: lazyground.robots reads robot.yaml through this package's typed_yaml
    from lazyground.robots.complete import complete_robot

    overrides = dict(robot_overrides or {})
    if "xacro_args" in overrides:  # --xacro-arg wins key by key over the scene's robot.xacro_args
        overrides["xacro_args"] = {**scene.robot.xacro_args, **overrides["xacro_args"]}
    tools = []
    for i, tool in enumerate(scene.robot.tools):
        tool_model = resolve_model(tool.model, scene_dir)
        if tool_model is None:
            raise SceneError(f"{source}: robot.tools[{i}].model: model file {tool.model!r} not found")
        tools.append(replace(tool, model=str(tool_model)))
    robot = replace(scene.robot, model=str(model), tools=tuple(tools), **overrides)
    robot = complete_robot(robot, scene_dir, source)
    return replace(scene, robot=robot, obstacles=_absolute_meshes(scene.obstacles, scene_dir), source=source)


def load_scene(path: str | os.PathLike, robot_overrides: dict | None = None) -> Scene:
    """Load and validate a scene file; a bare name (``parking_1``) means the bundled scene
    (``robot_overrides``: see :func:`parse_scene`).

    Raises:
        SceneError: with one line naming the file, the key path and the problem.
    """
    path = Path(path)
    if not path.is_file():
        path = bundled_scene(str(path)) or path  # a bare name: the bundled scene, from any directory
    if path.is_dir():
        raise SceneError(f"{path}: is a folder, not a scene file")
    if not path.is_file():
        hint = f" (bundled scenes: {', '.join(scene_names())})" if Path(path).name == str(path) else ""
        raise SceneError(f"{path}: no such scene file{hint}")
    size = path.stat().st_size
    if size > MAX_SCENE_BYTES:
        raise SceneError(f"{path}: file is {size / 1e6:.0f} MB; scenes are limited to {MAX_SCENE_BYTES // 2**20} MiB")
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise SceneError(f"{path}: not a UTF-8 text file") from None
    # Parsed once per text: the same file unchanged gives the same (frozen) Scene; a robot's own files
    # (robot.yaml, models) are read as the loader always has, cached by path (they ship with the package).
    key = (str(path), text, repr(sorted((robot_overrides or {}).items())), os.environ.get("LAZYGROUND_MODELS", ""))
    scene = _SCENES.get(key)
    if scene is None:
        scene = parse_scene(text, str(path), path.parent, robot_overrides)
        _SCENES[key] = scene
        while len(_SCENES) > SCENE_CACHE_SIZE:
            _SCENES.popitem(last=False)
    else:
        _SCENES.move_to_end(key)
    return scene


def _not_a_scene(text: str, data: dict | None = None) -> str | None:
    """What a file given as a scene is instead (a robot model, a MoveIt message) and what to do with it, or None."""
    kind = kind_of_mapping(data) if data is not None else kind_of_text(text)
    model = "a scene names it under robot.model (docs/scene_format.md); `lazyground check-robot FILE` shows what it holds"
    hint = {
        FileKind.PLANNING_SCENE: "convert it with `lazyground import-moveit FILE -o scene.yaml`",
        FileKind.MOTION_PLAN_REQUEST: "give it to `lazyground plan SCENE REQUEST` as --start-from FILE",
        FileKind.URDF: model,
        FileKind.SDF: model,
        FileKind.SRDF: "give it as --srdf FILE or under robot.srdf in a scene",
        FileKind.XML: "a scene is YAML (docs/scene_format.md)",
        FileKind.SCENE_TEXT: "convert it with `lazyground import-moveit FILE -o scene.yaml`",
    }.get(kind)
    return f"this is {kind.value}, not a lazyground scene: {hint}" if hint else None


def _bundled() -> str:
    names = sorted({p.name for d in models_dirs() if d.is_dir() for p in d.iterdir() if p.is_dir()})
    return ", ".join(names) or "none"


def _overlap_problem(scene: Scene) -> str | None:
    """An object whose centre lies inside another solid (an object or an obstacle) is a modelling error; obstacles
    may overlap one another (boards that meet, generated racks)."""
    solids = [(f"objects[{i}]", "object", o) for i, o in enumerate(scene.objects) if o.collides]
    solids += [(f"obstacles[{i}]", "obstacle", o) for i, o in enumerate(scene.obstacles) if o.geometry.mesh is None]
    frames = [(np.asarray(X.xyz), X.rotation()) for X in (b.pose.pose() for _, _, b in solids)]  # once per solid
    hits = []  # (the larger one holds the centre, later solid first, message)
    for n, (key, kind, a) in enumerate(solids):
        if kind == "obstacle":
            continue
        centre = np.asarray(a.pose.xyz, dtype=float)
        for (_, other_kind, b), (p_WB, R_WB) in zip(solids, frames):
            if b is a:
                continue
            if b.geometry.contains((centre - p_WB) @ R_WB):
                message = f"{key}.pose: {kind} {a.id!r} has its centre inside {other_kind} {b.id!r}"
                hits.append((a.geometry.volume() > b.geometry.volume(), -n, message))
    return min(hits)[2] if hits else None


def _mesh_path(file: str, scene_dir: Path | None) -> Path:
    path = Path(file)
    return path if path.is_absolute() or scene_dir is None else scene_dir / path


def _mesh_problem(scene: Scene, scene_dir: Path | None) -> str | None:
    for i, o in enumerate(scene.obstacles):
        if o.geometry.mesh is not None and not _mesh_path(o.geometry.mesh.file, scene_dir).is_file():
            return f"obstacles[{i}].geometry.mesh.file: {o.id!r}: no such file {o.geometry.mesh.file!r}"
    return None


def _absolute_meshes(obstacles, scene_dir: Path | None):
    """Mesh files resolved against the scene's folder: Drake opens them later from any cwd."""
    out = []
    for o in obstacles:
        m = o.geometry.mesh
        if m is not None:
            o = replace(o, geometry=replace(o.geometry, mesh=replace(m, file=str(_mesh_path(m.file, scene_dir).resolve()))))
        out.append(o)
    return tuple(out)
