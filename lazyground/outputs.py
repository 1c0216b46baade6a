"""Checks on the CLI's output options that can be made before planning (#20: fail in the first second, not after)."""

from __future__ import annotations

import tempfile
from pathlib import Path

from lazyground.scene.schema import Scene
from lazyground.typed_yaml import SceneError
from lazyground.viz.trace import planar_indices

HTML_SUFFIXES = (".html", ".htm")
YAML_SUFFIXES = (".yaml", ".yml")


def output_problem(scene: Scene, html: str | None = None, plot: str | None = None, animate: str | None = None,
                   files: dict[str, str | None] | None = None) -> str | None:
    """What is wrong with the requested output files for this scene, or None.

    ``--plot``/``--animate`` draw a planar robot from above; every file needs an existing folder
    in which it can be written, and a suffix its writer knows (``files``: more output files by
    flag, e.g. ``--trajectory``, ``--ros-trajectory``).
    """
    for flag, value in (("--html", html), ("--plot", plot), ("--animate", animate), *(files or {}).items()):
        if value is None:
            continue
        problem = _file_problem(Path(value).expanduser()) or _suffix_problem(flag, Path(value).suffix.lower())
        if problem:
            return f"{flag} {value}: {problem}"
    if plot or animate:
        try:
            planar_indices(scene.robot.planned_joints or tuple(scene.robot.start))
        except SceneError as exc:
            flag = "--plot" if plot else "--animate"
            return f"{flag}: {exc} (use --html for a 3-D replay)"
    return None


def folder_problem(folder: Path) -> str | None:
    """Why files cannot be written into ``folder`` (made if missing), or None."""
    if folder.exists() and not folder.is_dir():
        return "is a file, not a folder"
    try:
        folder.mkdir(parents=True, exist_ok=True)
        tempfile.TemporaryFile(dir=folder).close()
    except OSError as exc:
        return f"cannot write there: {exc.strerror or exc}"
    return None


def _file_problem(path: Path) -> str | None:
    """Why ``path`` cannot be written (a missing folder, a folder, no permission), or None.

    A file that did not exist is created to find out, then removed: a check of the permission bits
    says nothing for root or on a read-only or virtual file system."""
    folder = path.resolve().parent
    if not folder.is_dir():
        return f"folder {folder} does not exist"
    if path.is_dir():
        return "is a folder; give a file name"
    existed = path.exists()
    try:
        with open(path, "ab"):
            pass
    except OSError as exc:
        return f"cannot write: {exc.strerror or exc}"
    if not existed:
        path.unlink(missing_ok=True)
    return None


def _suffix_problem(flag: str, suffix: str) -> str | None:
    """Why a file of this suffix cannot be what ``flag`` writes, or None."""
    known = _suffixes(flag)
    if known is None or suffix in known:
        return None
    return f"{'no suffix' if not suffix else f'unknown suffix {suffix!r}'}; {flag} writes {', '.join(known)}"


def _suffixes(flag: str) -> tuple[str, ...] | None:
    """The suffixes the writer behind ``flag`` understands (None: no check here)."""
    if flag == "--html":
        return HTML_SUFFIXES
    if flag == "--ros-trajectory":
        return YAML_SUFFIXES
    if flag == "--plot":  # matplotlib's savefig picks the format by suffix (and appends .png to none)
        from matplotlib.backend_bases import FigureCanvasBase

        return tuple(f".{s}" for s in sorted(FigureCanvasBase.get_supported_filetypes()))
    if flag == "--animate":  # Pillow writes every frame only in these formats
        from PIL import Image

        return tuple(sorted(s for s, fmt in Image.registered_extensions().items() if fmt in Image.SAVE_ALL))
    return None
