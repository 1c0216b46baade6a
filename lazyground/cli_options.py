"""The CLI's option groups over the library: argparse stops here; the library takes plain values.

- the settings flags (one per CLI-layer declaration of :mod:`lazyground.settings`);
- the start-state options of ``import-moveit`` and ``plan`` (:class:`lazyground.moveit.start.StartOptions`);
- the motion options that are not settings (``--no-shortcut``, trajectory files).

``python3 -m lazyground.cli_options`` prints the settings table of docs/scene_format.md.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from lazyground.motion import TRAJECTORY_FORMATS as FORMATS  # the package only: the CLI starts fast
from lazyground.settings import Layer, Setting, declared, markdown_table


def add_motion_options(p) -> None:
    """The motion flags that are not settings (those come from lazyground.settings: --speed, ...)."""
    p.add_argument("--no-shortcut", action="store_true", help="keep the planner's raw path (--shortcut-iterations 0)")
    p.add_argument("--trajectory", metavar="FILE", help="write the timed trajectory (.csv or .json)")
    p.add_argument("--ros-trajectory", metavar="FILE", help="write a trajectory_msgs/JointTrajectory YAML")


def motion_overrides(args) -> dict:
    """The settings these flags imply (``--no-shortcut``), after checking them.

    Raises:
        ValueError: a bad option (one line, for exit 2).
    """
    if args.trajectory and Path(args.trajectory).suffix.lower() not in FORMATS:
        raise ValueError(f"--trajectory: {args.trajectory} must end in {' or '.join(FORMATS)}")
    return {"shortcut_iterations": 0} if args.no_shortcut else {}


def add_start_options(parser) -> None:
    """The start options of ``import-moveit`` and ``plan`` (one definition for both)."""
    group = parser.add_argument_group("start state")
    group.add_argument("--start", metavar="NAME", help="start from a named pose of the robot (models/<robot>/robot.yaml, e.g. tucked)")
    group.add_argument("--start-from", metavar="REQUEST.yaml",
                       help="start from a MoveIt motion-plan request's start_state.joint_state")
    group.add_argument("--start-joints", metavar="NAME=VALUE,...",
                       help="set these joints (applied after --start/--start-from), e.g. torso_lift_joint=0.2")


def start_options(args):
    """The :class:`~lazyground.moveit.start.StartOptions` of parsed arguments."""
    from lazyground.moveit.start import StartOptions  # in here: lazyground.moveit is slow to import

    return StartOptions(args.start, args.start_from, args.start_joints)


# --- the settings flags --------------------------------------------------------------------------------------

def add_cli_options(parser: argparse.ArgumentParser) -> None:
    """One ``--flag`` per CLI-layer setting; names are argparse choices, numbers are range-checked
    by :func:`cli_values` (so the message reads ``--goal-bias must be in [0, 1], got 2``)."""
    for s in declared(Layer.CLI):
        if s.type is bool:  # --reach-prior / --no-reach-prior
            parser.add_argument(s.flag, dest=s.name, action=argparse.BooleanOptionalAction, default=None,
                                help=f"{s.doc} (default: {_cli_default(s)})")
            continue
        parser.add_argument(s.flag, dest=s.name, type=str if s.choices else s.type, choices=s.choices,
                            metavar=None if s.choices else s.name.upper(),
                            help=f"{s.doc} ({'' if s.choices else s.allowed() + '; '}default: {_cli_default(s)})")


def _cli_default(s: Setting) -> str:
    return "the scene's" if Layer.SCENE in s.layers else f"{s.default:g}"


def cli_values(args: argparse.Namespace) -> dict[str, Any]:
    """The CLI-layer settings given on the command line, checked (None: not given).

    Raises:
        ValueError: one line naming the flag and its allowed values.
    """
    out = {}
    for s in declared(Layer.CLI):
        value = getattr(args, s.name)
        problem = s.problem(value) if value is not None else None
        if problem:
            raise ValueError(f"{s.flag} {problem}")
        out[s.name] = value
    return out


if __name__ == "__main__":
    print(markdown_table(), end="")
