"""Robot descriptions as they come: URDF/SDF files with ``package://`` meshes in STL, DAE or OBJ.

``prepare_model(path, packages)`` reads a URDF or SDF file and returns its text with every
mesh reference rewritten to an absolute path of a file Drake loads (OBJ):

* ``package://NAME/rel`` resolves through, in order, the given ``packages`` ({NAME: DIR},
  from a scene's ``robot.packages`` or ``--package NAME=DIR``), the package the model file
  itself sits in (the nearest ``package.xml`` above it), its sibling packages, and
  ``ROS_PACKAGE_PATH`` (every folder below it holding a ``package.xml``), as ROS does;
* ``file://`` and plain paths resolve against the model file's folder;
* STL (binary or ASCII) is converted to OBJ here with numpy (the format is a list of
  triangles; no dependency needed), DAE through ``trimesh`` (+ ``pycollada``) when
  installed (an optional dependency: ``pip install 'lazyground[meshes]'``); other formats
  Drake reads (OBJ, glTF, VTK) are used as they are. Converted files are cached by content
  hash under ``$LAZYGROUND_CACHE`` (default ``~/.cache/lazyground/meshes``).

Every problem is a ``SceneError`` with one line naming the file and what to do. No pydrake.
"""

from __future__ import annotations

import hashlib
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lazyground.mesh_files import MeshFileError, mesh_from_triangles, obj_text, read_stl
from lazyground.typed_yaml import SceneError

DRAKE_MESHES = (".obj", ".gltf", ".glb", ".vtk")
CONVERTED = (".stl", ".dae")
_MESH_TAGS = {"urdf": ("mesh", "filename"), "sdf": ("uri", None)}


@dataclass(frozen=True)
class PreparedModel:
    """A model's text ready for Drake's parser, and what was done to get it."""

    text: str
    file_type: str  # "urdf" or "sdf"
    meshes: dict[str, str] = field(default_factory=dict)  # original reference -> file Drake loads
    converted: tuple[str, ...] = ()  # references converted to OBJ
    packages: dict[str, str] = field(default_factory=dict)  # every package name that was resolved -> dir


def package_xml_name(folder: Path) -> str | None:
    """The ``<name>`` in ``folder/package.xml`` (falls back to the folder name), or None without one."""
    xml = folder / "package.xml"
    if not xml.is_file():
        return None
    try:
        name = ET.parse(xml).getroot().findtext("name")
    except ET.ParseError:
        name = None
    return (name or folder.name).strip()


def discover_packages(model: Path, env: dict | None = None) -> dict[str, Path]:
    """Packages found as ROS finds them: the model's own package and its siblings, then ROS_PACKAGE_PATH."""
    found: dict[str, Path] = {}
    for parent in model.resolve().parents:
        name = package_xml_name(parent)
        if name is not None:
            found.setdefault(name, parent)
            for sibling in sorted(parent.parent.iterdir()):
                sibling_name = package_xml_name(sibling) if sibling.is_dir() else None
                if sibling_name is not None:
                    found.setdefault(sibling_name, sibling)
            break
    env = os.environ if env is None else env
    for root in filter(None, env.get("ROS_PACKAGE_PATH", "").split(os.pathsep)):
        root_path = Path(root)
        if not root_path.is_dir():
            continue
        for xml in sorted(root_path.rglob("package.xml")):
            found.setdefault(package_xml_name(xml.parent), xml.parent)
    return found


def parse_package(item: str) -> tuple[str, Path]:
    """One ``NAME=DIR`` (the CLI's ``--package``).

    Raises:
        SceneError: not NAME=DIR, or DIR is not a folder.
    """
    name, sep, folder = item.partition("=")
    if not sep or not name.strip() or not folder.strip():
        raise SceneError(f"--package {item!r}: expected NAME=DIR, e.g. --package ur_description=~/ws/src/ur_description")
    path = Path(folder.strip()).expanduser()
    if not path.is_dir():
        raise SceneError(f"--package {name.strip()}: {folder!r} is not a folder")
    return name.strip(), path.resolve()


def parse_package_args(items) -> dict[str, Path]:
    """``NAME=DIR`` strings (repeated ``--package``) as a mapping (see :func:`parse_package`)."""
    return dict(parse_package(item) for item in items or ())


def resolve_uri(uri: str, base: Path, packages: dict[str, Path], model: Path) -> Path:
    """The file a mesh reference names.

    Raises:
        SceneError: an unknown package, or a file that does not exist (one line, with what to do).
    """
    if uri.startswith("package://") or uri.startswith("model://"):
        scheme, rest = uri.split("://", 1)
        name, _, relative = rest.partition("/")
        if name not in packages:
            known = ", ".join(sorted(packages)) or "none"
            raise SceneError(f"{model}: mesh {uri!r}: unknown package {name!r} (known: {known}); give its folder with "
                             f"robot.packages: {{{name}: DIR}} in the scene, --package {name}=DIR, or ROS_PACKAGE_PATH")
        path = packages[name] / relative
    elif uri.startswith("file://"):
        path = Path(uri[len("file://"):])
    else:
        path = Path(uri)
    path = path if path.is_absolute() else base / path
    if not path.is_file():
        raise SceneError(f"{model}: mesh {uri!r}: file {path} not found; check the path or the package's folder")
    return path.resolve()


def _cache_dir() -> Path:
    root = os.environ.get("LAZYGROUND_CACHE") or Path.home() / ".cache" / "lazyground"
    return Path(root) / "meshes"


def _read_dae(path: Path) -> np.ndarray:
    try:
        import trimesh  # optional: DAE needs an XML scene-graph reader
    except ImportError:
        raise SceneError(f"{path}: DAE meshes need trimesh and pycollada (pip install 'lazyground[meshes]'), "
                         "or convert the mesh to OBJ") from None
    try:
        mesh = trimesh.load(str(path), force="mesh")
    except Exception as exc:  # trimesh raises many types for malformed files
        raise SceneError(f"{path}: cannot read the DAE mesh ({type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}); convert it to OBJ") from None
    return mesh_from_triangles(np.asarray(mesh.triangles, float))


def _read_stl(path: Path) -> tuple[np.ndarray, np.ndarray]:
    try:
        return read_stl(path)
    except MeshFileError as exc:
        raise SceneError(f"{exc}; convert it to OBJ") from None


def obj_for(mesh: Path) -> Path:
    """An OBJ file Drake loads for ``mesh`` (itself when Drake reads its format), converted and cached."""
    suffix = mesh.suffix.lower()
    if suffix in DRAKE_MESHES:
        return mesh
    if suffix not in CONVERTED:
        raise SceneError(f"{mesh}: mesh format {suffix or '(none)'} is not supported (Drake reads OBJ, glTF, VTK; "
                         "lazyground converts STL and DAE); convert it to OBJ")
    digest = hashlib.sha256(mesh.read_bytes()).hexdigest()[:20]
    out = _cache_dir() / f"{mesh.stem}-{digest}.obj"
    if not out.is_file():
        vertices, triangles = _read_stl(mesh) if suffix == ".stl" else _read_dae(mesh)
        if len(triangles) == 0:
            raise SceneError(f"{mesh}: the mesh has no triangles")
        tmp = out.with_suffix(".tmp")
        try:
            out.parent.mkdir(parents=True, exist_ok=True)
            tmp.write_text(obj_text(vertices, triangles))
            tmp.replace(out)  # atomic: concurrent runs never read half a file
        except OSError as exc:  # e.g. a read-only home in a container
            raise SceneError(f"{mesh}: cannot write the converted mesh to {out.parent}: {exc.strerror or exc}; "
                             "set LAZYGROUND_CACHE to a writable folder") from None
    return out


def model_file_type(path: Path) -> str:
    """``urdf`` or ``sdf`` from the extension (``.xacro`` is not expanded here)."""
    suffix = path.suffix.lower()
    if suffix == ".urdf":
        return "urdf"
    if suffix == ".sdf":
        return "sdf"
    if suffix == ".xacro":
        raise SceneError(f"{path}: xacro files must be expanded first: xacro {path.name} > {path.stem}")
    raise SceneError(f"{path}: robot model must be a .urdf or .sdf file")


def prepare_model(path: str | os.PathLike, packages: dict[str, Path] | None = None, env: dict | None = None) -> PreparedModel:
    """The model's text with every mesh reference resolved to a file Drake loads (see module docstring).

    Args:
        path: a URDF or SDF file.
        packages: package folders by name; they win over discovered ones.
        env: environment for ``ROS_PACKAGE_PATH`` (default: the process's).
    Returns:
        The rewritten text, its file type and what was resolved or converted.
    Raises:
        SceneError: unreadable XML, an unknown package, a missing or unsupported mesh (one line).
    """
    model = Path(path).resolve()
    file_type = model_file_type(model)
    try:
        tree = ET.parse(model)
    except (OSError, ET.ParseError) as exc:
        raise SceneError(f"{model}: cannot read the robot description: {str(exc).splitlines()[0]}") from None
    known = {**discover_packages(model, env), **{k: Path(v).expanduser().resolve() for k, v in (packages or {}).items()}}
    tag, attr = _MESH_TAGS[file_type]
    meshes: dict[str, str] = {}
    converted: list[str] = []
    used: dict[str, str] = {}
    # SDF <uri> also names materials and included models; only a <mesh>'s is a mesh
    parent = {child: element for element in tree.iter() for child in element} if file_type == "sdf" else {}
    for element in tree.iter():
        if _local(element.tag) != tag or (file_type == "sdf" and _local(getattr(parent.get(element), "tag", "")) != "mesh"):
            continue
        uri = (element.get(attr) if attr else element.text or "").strip()
        if not uri:
            continue
        if uri not in meshes:
            target = obj_for(resolve_uri(uri, model.parent, known, model))
            meshes[uri] = str(target)
            if target.suffix.lower() != Path(uri).suffix.lower():
                converted.append(uri)
            if "://" in uri and not uri.startswith("file://"):
                name = uri.split("://", 1)[1].split("/", 1)[0]
                used[name] = str(known[name])
        # Drake takes only file:// URIs (not bare paths) in a model parsed from a string
        if attr:
            element.set(attr, f"file://{meshes[uri]}")
        else:
            element.text = f"file://{meshes[uri]}"
    _register_namespaces(model)
    text = ET.tostring(tree.getroot(), encoding="unicode")
    return PreparedModel(text, file_type, meshes, tuple(converted), used)


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _register_namespaces(model: Path) -> None:
    """Keep prefixes such as ``drake:`` when the tree is written back (ElementTree renames them otherwise)."""
    try:
        for _, (prefix, uri) in ET.iterparse(model, events=("start-ns",)):
            ET.register_namespace(prefix, uri)
    except ET.ParseError:
        pass
