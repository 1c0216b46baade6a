"""Checks on the CLI's output options that can be made before planning (#20: fail in the first second, not after)."""

from __future__ import annotations

from pathlib import Path

from lazyground.scene.schema import Scene
from lazyground.scene.typed_yaml import SceneError
from lazyground.viz.trace import planar_indices


def output_problem(scene: Scene, html: str | None = None, plot: str | None = None, animate: str | None = None,
                   files: dict[str, str | None] | None = None) -> str | None:
    """What is wrong with the requested output files for this scene, or None.

    ``--plot``/``--animate`` draw a planar robot from above; every file needs an existing folder
    (``files``: more output files by flag, e.g. ``--trajectory``).
    """
    for flag, value in (("--html", html), ("--plot", plot), ("--animate", animate), *(files or {}).items()):
        if value is None:
            continue
        folder = Path(value).expanduser().resolve().parent
        if not folder.is_dir():
            return f"{flag} {value}: folder {folder} does not exist"
        if Path(value).is_dir():
            return f"{flag} {value}: is a folder; give a file name"
    if plot or animate:
        try:
            planar_indices(scene.robot.planned_joints or tuple(scene.robot.start))
        except SceneError as exc:
            flag = "--plot" if plot else "--animate"
            return f"{flag}: {exc} (use --html for a 3-D replay)"
    return None
