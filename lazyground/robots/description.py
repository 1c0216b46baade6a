"""Robot descriptions as they come: URDF/SDF/xacro files with ``package://`` meshes in STL, DAE or OBJ.

``prepare_model(path, packages)`` reads a URDF or SDF file (a xacro file expanded first,
robots/xacro_file.py; undeclared prefixes, unused tags and continuous limits handled by
robots/lenient_xml.py) and returns its text with every mesh reference rewritten to an
absolute path of a file Drake loads (OBJ); visuals are dropped for planning, and
unloadable visual meshes are drawn from the link's collision geometry:

* ``package://NAME/rel`` resolves through, in order, the given ``packages`` ({NAME: DIR},
  from a scene's ``robot.packages`` or ``--package NAME=DIR``), the package the model file
  itself sits in (the nearest ``package.xml`` above it), its sibling packages, and
  ``ROS_PACKAGE_PATH`` (every folder below it holding a ``package.xml``), as ROS does;
* ``file://`` and plain paths resolve against the model file's folder; an absolute path into
  another machine's install space (``/home/u/ws/install/NAME/share/NAME/meshes/a.dae``, as
  URDFs generated there carry) that does not exist here is read in the known package NAME;
* STL (binary or ASCII) is converted to OBJ here with numpy (the format is a list of
  triangles; no dependency needed), DAE through ``trimesh`` (+ ``pycollada``) when
  installed (an optional dependency: ``pip install 'lazyground[meshes]'``); other formats
  Drake reads (OBJ, glTF, VTK) are used as they are. Converted files are cached by content
  hash under ``$LAZYGROUND_CACHE`` (default ``~/.cache/lazyground/meshes``).

Every problem is a ``SceneError`` with one line naming the file and what to do. No pydrake.
"""

from __future__ import annotations

import copy
import hashlib
import io
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lazyground.mesh_files import MeshFileError, mesh_from_triangles, obj_text, read_stl
from lazyground.robots.lenient_xml import declare_prefixes, drop_world_weld, parse_lenient, strip_unused, unwrap_continuous_limits
from lazyground.robots.xacro_file import expand_xacro
from lazyground.typed_yaml import SceneError
from lazyground.user_cache import cache_dir

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
    stripped: dict[str, int] = field(default_factory=dict)  # tag planning does not use -> elements removed
    notes: tuple[str, ...] = ()  # what was changed so that Drake loads it (continuous limits, visuals)


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
        path = _installed_share(path, packages) or path
    if not path.is_file():
        share = [b for a, b in zip(path.parts, path.parts[1:]) if a == "share"]
        hint = (f"; if it is package {share[-1]!r} of another machine's install space, give its folder with "
                f"--package {share[-1]}=DIR or robot.packages") if share and share[-1] not in packages else ""
        raise SceneError(f"{model}: mesh {uri!r}: file {path} not found; check the path or the package's folder{hint}")
    return path.resolve()


def _installed_share(path: Path, packages: dict[str, Path]) -> Path | None:
    """A missing absolute path into some workspace's ``.../share/NAME/rest`` (a URDF generated on another machine)
    read as ``rest`` in the known package NAME, or None."""
    parts = path.parts
    for i in range(len(parts) - 2, 0, -1):
        if parts[i - 1] == "share" and parts[i] in packages:
            return packages[parts[i]].joinpath(*parts[i + 1:])
    return None


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
    out = cache_dir("meshes") / f"{mesh.stem}-{digest}.obj"
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
    """``urdf``, ``sdf`` or ``xacro`` from the extension (``.urdf.xacro`` is xacro)."""
    suffix = path.suffix.lower()
    if suffix in (".urdf", ".sdf", ".xacro"):
        return suffix[1:]
    raise SceneError(f"{path}: robot model must be a .urdf, .sdf or .xacro file")


def prepare_model(path: str | os.PathLike, packages: dict[str, Path] | None = None, env: dict | None = None,
                  xacro_args: dict | None = None, visual: bool = True, base_link: str | None = None) -> PreparedModel:
    """The model's text with every mesh reference resolved to a file Drake loads (see module docstring).

    Args:
        path: a URDF, SDF or xacro file.
        packages: package folders by name; they win over discovered ones.
        env: environment for ``ROS_PACKAGE_PATH`` (default: the process's).
        xacro_args: ``arg`` values for a xacro file.
        visual: keep visual geometry (for a viewer); without, only collision geometry is loaded.
        base_link: a link the scene welds itself (``robot.base``): a URDF's own fixed joint from
            ``world`` to it is removed.
    Returns:
        The rewritten text, its file type and what was resolved, converted, stripped or noted.
    Raises:
        SceneError: unreadable XML, a missing xacro argument, an unknown package, a missing or
            unsupported collision mesh (one line). Visual meshes never raise (see ``visual_fallback``).
    """
    model = Path(path).resolve()
    file_type = model_file_type(model)
    known = {**discover_packages(model, env), **{k: Path(v).expanduser().resolve() for k, v in (packages or {}).items()}}
    try:
        if file_type == "xacro":
            text = expand_xacro(model, xacro_args, known)
        else:
            text = model.read_text(encoding="utf-8", errors="replace")
        root = parse_lenient(text)
    except (OSError, ET.ParseError) as exc:
        raise SceneError(f"{model}: cannot read the robot description: {str(exc).splitlines()[0]}") from None
    if file_type == "xacro":
        file_type = "sdf" if _local(root.tag) == "sdf" else "urdf"
    notes: list[str] = []
    stripped = strip_unused(root) if file_type == "urdf" else {}
    notes += unwrap_continuous_limits(root) if file_type == "urdf" else []
    dropped = drop_world_weld(root, base_link) if file_type == "urdf" and base_link else None
    notes += [dropped] if dropped else []
    parent = {child: element for element in root.iter() for child in element}
    if not visual:
        for element in [e for e in root.iter() if _local(e.tag) == "visual"]:
            parent[element].remove(element)
    meshes: dict[str, str] = {}
    converted: list[str] = []
    used: dict[str, str] = {}
    failed_visuals: dict = {}  # link element -> the first problem with one of its visual meshes
    for element in list(root.iter()):
        uri = _mesh_uri(element, parent, file_type)
        if not uri:
            continue
        role = _role(element, parent)
        if uri not in meshes:
            try:
                target = obj_for(resolve_uri(uri, model.parent, known, model))
            except SceneError as exc:
                if role != "visual":
                    raise
                failed_visuals.setdefault(parent.get(_container(element, parent)), str(exc))
                continue
            meshes[uri] = str(target)
            if target.suffix.lower() != Path(uri).suffix.lower():
                converted.append(uri)
            if "://" in uri and not uri.startswith("file://"):
                name = uri.split("://", 1)[1].split("/", 1)[0]
                used[name] = str(known[name])
        # Drake takes only file:// URIs (not bare paths) in a model parsed from a string
        if file_type == "urdf":
            element.set("filename", f"file://{meshes[uri]}")
        else:
            element.text = f"file://{meshes[uri]}"
    failed_visuals.pop(None, None)
    if failed_visuals:
        for link in failed_visuals:
            draw_collision_as_visual(link)
        first = next(iter(failed_visuals.values()))
        notes.append(f"visual meshes of {len(failed_visuals)} link(s) not loadable, drawn from their collision geometry "
                     f"(first: {first})")
    _register_namespaces(text)
    return PreparedModel(ET.tostring(root, encoding="unicode"), file_type, meshes, tuple(converted), used,
                         stripped, tuple(notes))


def _mesh_uri(element, parent: dict, file_type: str) -> str:
    """The mesh file an element names, or "" (SDF ``<uri>`` also names materials and included models)."""
    if file_type == "urdf":
        return (element.get("filename") or "").strip() if _local(element.tag) == "mesh" else ""
    if _local(element.tag) != "uri" or _local(getattr(parent.get(element), "tag", "")) != "mesh":
        return ""
    return (element.text or "").strip()


def _container(element, parent: dict):
    """The ``<visual>`` or ``<collision>`` holding ``element`` (None outside both)."""
    while element is not None and _local(element.tag) not in ("visual", "collision"):
        element = parent.get(element)
    return element


def _role(element, parent: dict) -> str:
    container = _container(element, parent)
    return _local(container.tag) if container is not None else ""


def draw_collision_as_visual(link) -> None:
    """Replace a link's visuals with copies of its collision geometry (pose and shape only)."""
    for old in [c for c in link if _local(c.tag) == "visual"]:
        link.remove(old)
    for i, collision in enumerate([c for c in link if _local(c.tag) == "collision"]):
        visual = ET.SubElement(link, collision.tag.replace("collision", "visual"))
        if collision.get("name") is not None:  # SDF needs unique names
            visual.set("name", f"{collision.get('name')}_drawn_{i}")
        for child in collision:
            if _local(child.tag) in ("origin", "pose", "geometry"):
                visual.append(copy.deepcopy(child))


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1] if isinstance(tag, str) else ""


def _register_namespaces(text: str) -> None:
    """Keep prefixes such as ``drake:`` when the tree is written back (ElementTree renames them otherwise)."""
    try:
        for _, (prefix, uri) in ET.iterparse(io.StringIO(declare_prefixes(text)), events=("start-ns",)):
            ET.register_namespace(prefix, uri)
    except (ET.ParseError, ValueError):
        pass
