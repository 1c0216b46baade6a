"""The motion options of ``lazyground plan`` that are not settings (``--no-shortcut``, trajectory files)."""

from __future__ import annotations

from pathlib import Path

FORMATS = (".csv", ".json")  # trajectory file suffixes (lazyground.motion.export writes them; not imported here: the CLI starts fast)


def add_arguments(p) -> None:
    """The motion flags that are not settings (those come from lazyground.settings: --speed, ...)."""
    p.add_argument("--no-shortcut", action="store_true", help="keep the planner's raw path (--shortcut-iterations 0)")
    p.add_argument("--trajectory", metavar="FILE", help="write the timed trajectory (.csv or .json)")
    p.add_argument("--ros-trajectory", metavar="FILE", help="write a trajectory_msgs/JointTrajectory YAML")


def overrides_from_args(args) -> dict:
    """The settings these flags imply (``--no-shortcut``), after checking them.

    Raises:
        ValueError: a bad option (one line, for exit 2).
    """
    if args.trajectory and Path(args.trajectory).suffix.lower() not in FORMATS:
        raise ValueError(f"--trajectory: {args.trajectory} must end in {' or '.join(FORMATS)}")
    return {"shortcut_iterations": 0} if args.no_shortcut else {}
