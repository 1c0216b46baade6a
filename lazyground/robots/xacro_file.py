"""xacro descriptions as ROS 2 packages ship them: expanded here, without ROS.

``expand_xacro(path, args, packages)`` runs the PyPI ``xacro`` package (a core dependency:
a pure-Python wheel, and most ROS 2 descriptions ship only as ``.urdf.xacro``) with the
given ``arg`` values; ``$(find pkg)`` resolves through the same package map as
``package://`` (there is no ament index outside ROS: xacro's look-up is answered by ours). The expansion is cached by content
hash (the file, every file it included, the arguments and the package folders) under
``$LAZYGROUND_CACHE/xacro``. Every problem is one ``SceneError`` line: a missing required
argument names it and says how to give it. No pydrake.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import os
import sys
import threading
import types
from pathlib import Path

from lazyground.typed_yaml import SceneError
from lazyground.user_cache import cache_dir

XACRO_SUFFIXES = (".xacro",)
_LOCK = threading.Lock()  # xacro keeps its state in module globals


def is_xacro(path: Path) -> bool:
    """Whether ``path`` is a xacro file (``.xacro``, ``.urdf.xacro``)."""
    return path.suffix.lower() in XACRO_SUFFIXES


def xacro_value(value) -> str:
    """A scene/CLI value as xacro reads an argument (``true``/``false`` for booleans)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer():
        return str(int(value))
    return str(value)


def parse_xacro_arg(item: str) -> tuple[str, str]:
    """One ``NAME=VALUE`` (the CLI's ``--xacro-arg``; ``NAME:=VALUE`` as ROS writes it also works).

    Raises:
        SceneError: no ``=``, or an empty name.
    """
    name, sep, value = item.partition("=")
    name = name.rstrip(":").strip()
    if not sep or not name:
        raise SceneError(f"--xacro-arg {item!r}: expected NAME=VALUE, e.g. --xacro-arg ur_type=ur5e")
    return name, value.strip()


def parse_xacro_args(items) -> dict[str, str]:
    """Repeated ``--xacro-arg NAME=VALUE`` as a mapping."""
    return dict(parse_xacro_arg(item) for item in items or ())


def _digest(*parts: bytes) -> str:
    h = hashlib.sha256()
    for part in parts:
        h.update(hashlib.sha256(part).digest())
    return h.hexdigest()[:24]


def _file_hash(path: str) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError:
        return ""


def expand_xacro(path: str | os.PathLike, args: dict | None = None, packages: dict[str, Path] | None = None) -> str:
    """The URDF (or SDF) text of a xacro file.

    Args:
        path: the ``.xacro`` file.
        args: ``arg`` values (``ur_type: ur5e``); booleans become ``true``/``false``.
        packages: package folders by name, for ``$(find NAME)``.
    Returns:
        The expanded XML text.
    Raises:
        SceneError: a missing argument, an unknown package, or xacro's own error (one line).
    """
    path = Path(path).resolve()
    args = {str(k): xacro_value(v) for k, v in (args or {}).items()}
    packages = {k: str(Path(v).resolve()) for k, v in (packages or {}).items()}
    key = _digest(path.read_bytes(), str(path).encode(), json.dumps(args, sort_keys=True).encode(),
                  json.dumps(packages, sort_keys=True).encode())
    cached = cache_dir("xacro") / f"{path.name.replace('.', '_')}-{key}"  # no dots: with_suffix adds .xml/.json
    text = _cached(cached)
    if text is not None:
        return text
    text, includes = _run_xacro(path, args, packages)
    _store(cached, text, includes)
    return text


def _cached(base: Path) -> str | None:
    """The cached expansion when every file it included is unchanged."""
    try:
        manifest = json.loads(base.with_suffix(".json").read_text())
        if all(_file_hash(name) == digest for name, digest in manifest.items()):
            return base.with_suffix(".xml").read_text()
    except (OSError, ValueError, AttributeError):
        pass
    return None


def _store(base: Path, text: str, includes: list[str]) -> None:
    try:
        base.parent.mkdir(parents=True, exist_ok=True)
        for suffix, content in ((".xml", text), (".json", json.dumps({f: _file_hash(f) for f in includes}))):
            tmp = base.with_suffix(suffix + ".tmp")
            tmp.write_text(content)
            tmp.replace(base.with_suffix(suffix))  # the manifest last: a half-written cache is never read
    except OSError:
        pass  # a read-only cache only costs the next run an expansion


def _run_xacro(path: Path, args: dict[str, str], packages: dict[str, str]) -> tuple[str, list[str]]:
    try:
        import xacro
    except ImportError:  # a core dependency; a broken install still gets one line
        raise SceneError(f"{path}: expanding xacro needs the xacro package (pip install xacro)") from None

    def find(name: str) -> str:
        if name not in packages:
            known = ", ".join(sorted(packages)) or "none"
            raise SceneError(f"{path}: $(find {name}): unknown package {name!r} (known: {known}); give its folder with "
                             f"robot.packages: {{{name}: DIR}} in the scene, --package {name}=DIR, or ROS_PACKAGE_PATH")
        return packages[name]

    with _LOCK, _ament_index(find), contextlib.redirect_stderr(io.StringIO()), contextlib.redirect_stdout(io.StringIO()):
        xacro.all_includes.clear()
        try:
            doc = xacro.process_file(str(path), mappings=dict(args))
            text = doc.toprettyxml(indent="  ")
        except SceneError:
            raise
        except Exception as exc:  # xacro raises its own and Python's exceptions
            raise SceneError(_one_line(path, exc, args)) from None
        includes = [str(path)] + [str(Path(f).resolve()) for f in xacro.all_includes]
    return text, sorted(set(includes))


def _one_line(path: Path, exc: Exception, args: dict[str, str]) -> str:
    from xacro import substitution_args

    inner = getattr(exc, "exc", None) or exc
    if isinstance(inner, SceneError):
        return str(inner)
    if isinstance(inner, substitution_args.ArgException):
        name = str(inner.args[0]) if inner.args else str(inner)
        return (f"{path.name}: xacro argument {name!r} is required: give it with robot.xacro_args: {{{name}: VALUE}} "
                f"in the scene or --xacro-arg {name}=VALUE")
    message = " ".join(str(exc).split()) or type(inner).__name__
    if getattr(exc, "exc", None) is not None and str(exc.exc) not in message:
        message += f": {' '.join(str(exc.exc).split())}"
    return f"{path}: xacro cannot expand it: {message}"


@contextlib.contextmanager
def _ament_index(find):
    """xacro resolves ``$(find pkg)`` by ``ament_index_python.packages.get_package_share_directory``: ours, while expanding."""
    names = ("ament_index_python", "ament_index_python.packages")
    saved = {name: sys.modules.get(name) for name in names}
    index, packages = types.ModuleType(names[0]), types.ModuleType(names[1])
    packages.get_package_share_directory = find
    index.packages = packages
    sys.modules.update(zip(names, (index, packages)))
    try:
        yield
    finally:
        for name, module in saved.items():
            if module is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = module
