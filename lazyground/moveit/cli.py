"""The ``import-moveit`` subcommand's options and command (#15); ``lazyground.cli`` wires it in."""

from __future__ import annotations

import sys

from lazyground.cli_options import add_start_options, start_options

DESCRIPTION = """Convert a MoveIt planning scene (moveit_msgs/PlanningScene YAML, or MoveIt's text .scene export)
into a lazyground scene.
Object types come from id words (table_leg_1 is an obstacle, Can1 a can) checked against geometry;
meshes found on disk (OBJ, STL) become collision geometry (their convex hull); the scene gets no
planner block, so the robot's own settings (models/<robot>/robot.yaml) apply.
Exit codes: 0 written, 2 bad input (one line; nothing written), 3 internal error."""


def add_import_options(m) -> None:
    """The options of ``import-moveit`` (documented in ``--help`` and docs/importing_moveit.md)."""
    m.description = DESCRIPTION
    m.add_argument("file", help="the MoveIt planning scene (.yaml/.yml, or a text .scene: RViz's Scene Objects export)")
    m.add_argument("-o", "--output", required=True, help="the lazyground scene to write (replaced only on success)")
    m.add_argument("--robot", default="fetch", help="robot model name or path with a robot.yaml beside it (default: fetch)")
    m.add_argument("--type", action="append", default=[], metavar="REGEX=TYPE",
                   help="type objects whose id matches REGEX (case-insensitive search) as TYPE, before the built-in "
                        "rules, without geometry checks; TYPE 'obstacle' = untyped; repeatable, first match wins")
    m.add_argument("--rules", metavar="FILE", help="a YAML file of 'REGEX: TYPE' rules, tried after --type")
    m.add_argument("--package", action="append", default=[], metavar="NAME=DIR",
                   help="resolve package://NAME/... mesh resources under DIR (repeatable)")
    m.add_argument("--srdf", metavar="FILE", help="the robot's SRDF (MoveIt's disabled collision pairs and named "
                   "states), written into the scene's robot block")
    m.add_argument("--xacro-arg", action="append", default=[], metavar="NAME=VALUE",
                   help="an argument of a .xacro robot model, written into the scene's robot.xacro_args (repeatable)")
    m.add_argument("--name", help="the scene name (default: the output file's stem)")
    add_start_options(m)
    m.add_argument("--debug", action="store_true", help="show tracebacks")


def cmd_import_moveit(args) -> int:
    """Run the import; warnings and notes to stderr, the summary and planner to stdout."""
    from lazyground.moveit.convert import ImportOptions
    from lazyground.moveit.importer import import_moveit_file
    from lazyground.robots.description import parse_package_args
    from lazyground.robots.xacro_file import parse_xacro_args
    from lazyground.moveit.types import load_rules_file, parse_rule

    rules = [parse_rule(t) for t in args.type] + (load_rules_file(args.rules) if args.rules else [])
    options = ImportOptions(robot=args.robot, user_rules=tuple(rules), packages=parse_package_args(args.package),
                            start=start_options(args), name=args.name or ImportOptions().name, srdf=args.srdf,
                            xacro_args=parse_xacro_args(args.xacro_arg))
    result = import_moveit_file(args.file, args.output, options)
    for line in result.summary.warnings:
        print(f"warning: {line}", file=sys.stderr)
    for line in result.summary.notes:
        print(f"note: {line}", file=sys.stderr)
    print(f"wrote {args.output}: {result.summary.line()}")
    print(f"planner: {result.planner}")
    return 0
