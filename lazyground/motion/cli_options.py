"""The motion options of ``lazyground plan`` (shortcut, speed, trajectory files)."""

from __future__ import annotations

import sys
from pathlib import Path

FORMATS = (".csv", ".json")  # as lazyground.motion.export (imported lazily: the CLI starts fast)


def add_arguments(p) -> None:
    p.add_argument("--no-shortcut", action="store_true", help="keep the planner's raw path (no shortcutting)")
    p.add_argument("--shortcut-time", type=float, help="shortcutting time budget, seconds (default 1)")
    p.add_argument("--shortcut-iterations", type=int, help="shortcut attempts (default 100)")
    p.add_argument("--speed", type=float, help="0 < s <= 1: velocity limits x s, acceleration limits x s^2 (default 1)")
    p.add_argument("--sample-rate", type=float, help="trajectory samples per second (default 100)")
    p.add_argument("--trajectory", metavar="FILE", help="write the timed trajectory (.csv or .json)")
    p.add_argument("--ros-trajectory", metavar="FILE", help="write a trajectory_msgs/JointTrajectory YAML")


def settings_from_args(args):
    """MotionSettings from the parsed options.

    Raises:
        ValueError: an option is out of range (one line, for exit 2).
    """
    from lazyground.motion.pipeline import MotionSettings

    if args.trajectory and Path(args.trajectory).suffix.lower() not in FORMATS:
        raise ValueError(f"--trajectory: {args.trajectory} must end in {' or '.join(FORMATS)}")
    given = {"shortcut_time": args.shortcut_time, "shortcut_iterations": args.shortcut_iterations,
             "speed": args.speed, "sample_rate": args.sample_rate}
    try:
        return MotionSettings(shortcut=not args.no_shortcut, **{k: v for k, v in given.items() if v is not None})
    except ValueError as exc:
        raise ValueError(f"motion options: {exc}") from None


def write_outputs(report, args, out=sys.stdout) -> None:
    """Write --trajectory / --ros-trajectory for a solved report (pick and place: the steps joined)."""
    if not (args.trajectory or args.ros_trajectory):
        return
    from lazyground.motion.export import write_ros_trajectory, write_trajectory
    from lazyground.motion.steps import report_trajectory

    traj = report_trajectory(report)
    if traj is None:
        print("note: no trajectory to write" + (f" ({report.motion.note})" if report.motion and report.motion.note else ""), file=out)
        return
    if args.trajectory:
        write_trajectory(traj, args.trajectory)
        print(f"wrote {args.trajectory}", file=out)
    if args.ros_trajectory:
        write_ros_trajectory(traj, args.ros_trajectory)
        print(f"wrote {args.ros_trajectory}", file=out)
