"""The ``lazyground`` command: a thin ``main(argv) -> int`` over library calls.

Exit codes: 0 solved / done, 1 a planning failure status (timeout, invalid
start, no valid goal), 2 bad input (scene, request, arguments, an output file
that cannot be written), 3 an internal
error (a bug: ``--debug`` shows the traceback), 130 interrupted, 141 the reader
of the output went away (``lazyground plan ... --json | head``: silent, as any
Unix tool stopped by SIGPIPE).
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import traceback
from pathlib import Path

from lazyground.interrupt import work_begins
from lazyground import cli_options

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_PIPE_CLOSED = 0, 1, 2, 3, 130, 141


class UsageError(Exception):
    """Bad command-line input (exit 2)."""


class _StoreOnce(argparse.Action):
    """A value option given twice is refused (argparse's own "store" keeps the last one silently)."""

    def __call__(self, parser, namespace, values, option_string=None):
        given = namespace.__dict__.setdefault(_GIVEN, set())
        if self.dest in given:
            raise argparse.ArgumentError(self, "given twice; give it once")
        given.add(self.dest)
        setattr(namespace, self.dest, values)


_GIVEN = "_options_given"


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.register("action", None, _StoreOnce)
        self.register("action", "store", _StoreOnce)

    def parse_known_args(self, args=None, namespace=None):
        namespace, rest = super().parse_known_args(args, namespace)
        namespace.__dict__.pop(_GIVEN, None)
        return namespace, rest

    def error(self, message):  # one line, exit 2, no usage dump
        raise UsageError(message)


def _add_robot_source_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--package", action="append", metavar="NAME=DIR",
                   help="folder of the ROS package NAME for package://NAME/... URIs in the robot model (repeatable)")
    p.add_argument("--srdf", metavar="FILE", help="MoveIt SRDF: disabled collision pairs and named poses")
    p.add_argument("--xacro-arg", action="append", metavar="NAME=VALUE",
                   help="an argument of a .xacro robot model, e.g. ur_type=ur5e (repeatable; wins over robot.xacro_args)")


def _robot_overrides(args) -> dict:
    """The scene robot keys that --package/--srdf/--xacro-arg replace (paths made absolute: they are relative to the cwd)."""
    from lazyground.robots.description import parse_package_args
    from lazyground.robots.xacro_file import parse_xacro_args

    out: dict = {}
    packages = parse_package_args(getattr(args, "package", None))
    if packages:
        out["packages"] = {name: str(folder.resolve()) for name, folder in packages.items()}
    if getattr(args, "srdf", None):
        out["srdf"] = str(Path(args.srdf).resolve())
    xacro_args = parse_xacro_args(getattr(args, "xacro_arg", None))
    if xacro_args:
        out["xacro_args"] = xacro_args
    return out


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="lazyground", description="Ground ambiguous requests lazily inside a motion planner.")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    parser.add_argument("--version", action="store_true", help="print the version and exit")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)

    p = sub.add_parser("plan", help="ground a request and plan to whichever interpretation is reachable")
    p.add_argument("scene")
    p.add_argument("request")
    cli_options.add_cli_options(p)
    _add_robot_source_options(p)
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--html", metavar="FILE", help="write a self-contained HTML replay (Meshcat)")
    p.add_argument("--meshcat", action="store_true", help="show the result in a live Meshcat until Ctrl-C")
    p.add_argument("--loop-once", action="store_true", help="with --meshcat: draw once and return (tests)")
    p.add_argument("--plot", metavar="FILE", help="parking scenes: write a top-down PNG")
    p.add_argument("--animate", metavar="FILE", help="parking scenes: write a top-down GIF")
    p.add_argument("--debug", action="store_true", help="show tracebacks")
    cli_options.add_motion_options(p)

    g = sub.add_parser("ground", help="print the interpretations of a request and their goal regions")
    g.add_argument("scene")
    g.add_argument("request")
    g.add_argument("--json", action="store_true")
    _add_robot_source_options(g)
    g.add_argument("--debug", action="store_true", help="show tracebacks")

    c = sub.add_parser("check-robot", help="load a robot model (URDF/SDF) and report what lazyground makes of it")
    c.add_argument("model", help="a URDF, SDF or xacro file, or a bundled robot name (fetch, panda, ur5e)")
    _add_robot_source_options(c)
    c.add_argument("--write-allowed", metavar="FILE", help="sample configurations and write the link pairs to stop "
                   "checking (adjacent, always and never touching) as robot.allowed_collisions YAML, or an SRDF (.srdf)")
    c.add_argument("--samples", type=int, metavar="N", help="configurations to sample (default 200; 1000 with --write-allowed)")
    c.add_argument("--seed", type=int, default=0, help="seed of the sampled configurations (default 0)")
    c.add_argument("--debug", action="store_true", help="show tracebacks")

    d = sub.add_parser("demo", help="plan the bundled demo requests and write the visualisations")
    d.add_argument("--out", default="lazyground_output", help="output folder (default: lazyground_output)")
    d.add_argument("--seed", type=int, default=0)
    d.add_argument("--debug", action="store_true", help="show tracebacks")

    from lazyground.moveit.cli import add_import_options

    cli_options.add_start_options(p)
    add_import_options(sub.add_parser("import-moveit", help="convert a MoveIt planning-scene YAML into a lazyground scene"))

    gen = sub.add_parser("generate", help="write a generated scene: a parking lot or a rack of cubbies (issue #33)")
    gen.add_argument("family", choices=("lot", "rack"))
    gen.add_argument("--robot", default="panda", help="rack: panda or fetch (default: panda)")
    gen.add_argument("--free", type=int, help="lot: free spots (default 64)")
    gen.add_argument("--objects", type=int, help="rack: cans (default 16)")
    gen.add_argument("--reachable", type=int, help="how many are reachable (default: lot 2, rack 1)")
    gen.add_argument("--seed", type=int, default=0)
    gen.add_argument("--slots", type=int, help="lot: a fixed layout of this many spots, the blocked ones not free parked")
    gen.add_argument("-o", "--output", metavar="FILE", help="write the scene YAML here (default: stdout)")
    gen.add_argument("--debug", action="store_true", help="show tracebacks")

    b = sub.add_parser("bench", help="benchmark strategies and peers (see benchmarks/RESULTS.md)", add_help=False)
    b.add_argument("bench_args", nargs=argparse.REMAINDER)
    return parser


def cmd_ground(args) -> int:
    import grounding
    from lazyground.scene import load_scene

    scene = load_scene(args.scene, _robot_overrides(args))
    g = grounding.ground(args.request, scene)
    if args.json:
        print(json.dumps(g.to_json()))
        return EXIT_OK
    print(f"request: {args.request!r} -> action {g.action}, {len(g.interpretations)} interpretation(s)" + (" (ambiguous: all kept)" if g.ambiguous else ""))
    for note in g.notes:
        print(f"note: {note}")
    for i in g.interpretations:
        target = f" onto {i.target}" if i.target else ""
        print(f"  {i.id}: {i.action} {', '.join(i.objects)}{target}")
        for r in i.goal_regions + i.place_regions:
            print(f"    region {r.id} ({r.kind}{', ' + r.label if r.label else ''})")
    return EXIT_OK


def _import_drake() -> None:
    """Import the Drake side with Ctrl-C held back until done: pydrake logs a stack trace and
    fails to import when interrupted midway. A Ctrl-C pressed meanwhile is raised right after."""
    pressed = []
    old = signal.signal(signal.SIGINT, lambda *_: pressed.append(True))
    try:
        import lazyground.drake.ik  # noqa: F401  (imports lazyground.drake.world)
    except ImportError:
        pass  # no pydrake: planning says so when it needs it
    finally:
        signal.signal(signal.SIGINT, old)
    if pressed:
        raise KeyboardInterrupt


def cmd_plan(args) -> int:
    from lazyground import api
    from lazyground.moveit.start import override_scene_start
    from lazyground.outputs import output_problem
    from lazyground.report import report_lines, report_to_json
    from lazyground.scene import load_scene

    scene, start_warnings = override_scene_start(load_scene(args.scene, _robot_overrides(args)), cli_options.start_options(args))
    for line in start_warnings:
        print(f"warning: {line}", file=sys.stderr)
    try:
        overrides = cli_options.cli_values(args) | cli_options.motion_overrides(args)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    try:  # the scene's settings with the options, together (e.g. an edge_resolution too fine for the step)
        api.planner_settings(scene, **{k: v for k, v in overrides.items() if k != "seed"})  # the seed is no setting
    except ValueError as exc:
        raise UsageError(f"{scene.source or scene.name}: {exc}") from None
    problem = output_problem(scene, args.html, args.plot, args.animate,
                             {"--trajectory": args.trajectory, "--ros-trajectory": args.ros_trajectory})
    if problem:
        raise UsageError(problem)
    visual = bool(args.html or args.meshcat or args.plot or args.animate)
    _import_drake()
    work_begins()
    from lazyground.drake import compiled

    compiled_before = compiled.compile_report()
    report = api.plan(scene, args.request, keep_tree=visual, **overrides)
    if compiled_before is None:
        _say_compiled(compiled.compile_report())
    if args.json:
        print(json.dumps(report_to_json(report)))
    else:
        print("\n".join(report_lines(report)))
    res = report.result
    if res.status.value == "interrupted":  # Ctrl-C inside the planner: the partial statistics are printed above
        print(f"interrupted after {report.time_s:.1f} s: {res.iterations} iterations, tree {res.tree_size}, "
              f"{len(res.goal_samples)} goal samples", file=sys.stderr)
        return EXIT_INTERRUPTED
    if res.status.value == "invalid_start":  # #15: say which start would do
        from lazyground.drake.start_check import start_hint

        print(f"hint: {start_hint(scene)}", file=sys.stderr)
    _write_visuals(report, scene, args)
    if res.solved:
        from lazyground.motion.export import write_outputs

        flags = [f"{flag} {path}" for flag, path in (("--trajectory", args.trajectory), ("--ros-trajectory", args.ros_trajectory)) if path]
        lines = _writing(" / ".join(flags), lambda: write_outputs(report, args.trajectory, args.ros_trajectory))
        for line in lines:
            print(line, file=sys.stderr if args.json else sys.stdout)
    return EXIT_OK if res.solved else EXIT_FAILED


def _say_compiled(done: tuple[float, bool] | None) -> None:
    """One line on stderr when this run compiled the kernels (the first on a machine: tens of seconds)."""
    if done and done[1]:
        print(f"note: compiled the planner's kernels in {done[0]:.0f} s, within the world build (once per machine: "
              "numba caches them)", file=sys.stderr)


def _writing(what: str, write):
    """``write()``; an OSError (disk full, the file made read-only meanwhile) is bad input naming the output."""
    try:
        return write()
    except OSError as exc:
        raise UsageError(f"{what}: cannot write: {exc.strerror or exc}") from None


def _write_visuals(report, scene, args) -> None:
    out = sys.stderr if args.json else sys.stdout
    if args.plot or args.animate:
        from lazyground.viz import plots

        if args.plot:
            _writing(f"--plot {args.plot}", lambda: plots.plot_parking(report, scene, args.plot))
            print(f"wrote {args.plot}", file=out)
        if args.animate:
            _writing(f"--animate {args.animate}", lambda: plots.animate_parking(report, scene, args.animate))
            print(f"wrote {args.animate}", file=out)
    if args.html or args.meshcat:
        from lazyground.viz import meshcat_view

        if args.html:
            size = _writing(f"--html {args.html}", lambda: meshcat_view.write_html(report, scene, args.html))
            print(f"wrote {args.html} ({size / 1e6:.1f} MB)", file=out)
        if args.meshcat:
            meshcat_view.show_live(report, scene, loop_once=args.loop_once, say=lambda line: print(line, file=out, flush=True))


def cmd_demo(args) -> int:
    from lazyground.outputs import folder_problem
    from lazyground.settings import BY_NAME
    from lazyground.viz.demo import run_demo

    problem = BY_NAME["seed"].problem(args.seed)
    if problem:
        raise UsageError(f"--seed {problem}")
    problem = folder_problem(Path(args.out))
    if problem:
        raise UsageError(f"--out {args.out}: {problem}")
    work_begins()
    return run_demo(Path(args.out), seed=args.seed, say=print)


def cmd_check_robot(args) -> int:
    """Exit 0 when the robot is fine, 2 with the problems (the last line says which)."""
    from lazyground.robots.description import parse_package_args
    from lazyground.robots.xacro_file import parse_xacro_args
    from lazyground.scene.loader import resolve_model
    from lazyground.typed_yaml import SceneError

    model = resolve_model(args.model, Path.cwd())
    if model is None:
        raise SceneError(f"check-robot: no model file {args.model!r} (give a .urdf/.sdf/.xacro path or a bundled robot name)")
    _import_drake()
    from lazyground.drake.check_robot import check_robot

    if args.samples is not None and args.samples < 1:
        raise UsageError(f"--samples {args.samples}: must be at least 1")
    report = check_robot(model, args.srdf, parse_package_args(args.package), parse_xacro_args(args.xacro_arg),
                         args.write_allowed, args.samples, args.seed)
    for line in report.lines():
        print(line)
    return EXIT_OK if report.ok else EXIT_BAD_INPUT


def cmd_import_moveit(args) -> int:
    from lazyground.moveit.cli import cmd_import_moveit as run

    return run(args)


def cmd_generate(args) -> int:
    from lazyground.bench.families import generate, parse_key, scene_yaml

    if args.family == "lot":
        key = f"lot:{64 if args.free is None else args.free}:{2 if args.reachable is None else args.reachable}:{args.seed}"
        key += f":{args.slots}" if args.slots else ""
    else:
        key = f"rack:{args.robot}:{16 if args.objects is None else args.objects}:{1 if args.reachable is None else args.reachable}:{args.seed}"
    try:
        text = scene_yaml(generate(parse_key(key)))
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    if args.output is None:
        sys.stdout.write(text)
        return EXIT_OK
    try:
        Path(args.output).write_text(text)
    except OSError as exc:
        raise UsageError(f"cannot write {args.output}: {exc.strerror or exc}") from None
    print(f"wrote {args.output}", file=sys.stderr)
    return EXIT_OK


def cmd_bench(args) -> int:
    from lazyground.bench.cli import main as bench_main

    work_begins()
    return bench_main(args.bench_args)


COMMANDS = {"plan": cmd_plan, "ground": cmd_ground, "demo": cmd_demo, "import-moveit": cmd_import_moveit, "bench": cmd_bench,
            "generate": cmd_generate, "check-robot": cmd_check_robot}


def main(argv: list[str] | None = None) -> int:
    as_program = argv is None
    try:
        code = _main(sys.argv[1:] if argv is None else list(argv))
    except KeyboardInterrupt:  # Ctrl-C while the imports below were still running
        print("interrupted", file=sys.stderr)
        code = EXIT_INTERRUPTED
    if as_program:  # the work is done: a Ctrl-C during interpreter shutdown must not turn the exit code into -2
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    if code == EXIT_INTERRUPTED and as_program:
        # CPython exits by SIGINT (status -2, not 130) when the Ctrl-C landed in code an
        # extension module ran through PyRun_* (pydrake's imports), even once handled.
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    return code


def _silence_stdout() -> None:
    """Point stdout at /dev/null, so the interpreter's final flush of a closed pipe raises nothing."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


def _interrupted(exc: BaseException) -> bool:
    """Whether ``exc`` was caused by Ctrl-C (pydrake turns it into "ImportError: initialization failed")."""
    while exc is not None:
        if isinstance(exc, KeyboardInterrupt):
            return True
        exc = exc.__cause__ or exc.__context__
    return False


def _main(argv: list[str]) -> int:
    debug = "--debug" in argv
    from grounding.model import GroundingError
    from lazyground.typed_yaml import SceneError

    try:
        if argv[:1] == ["bench"]:  # argparse's REMAINDER drops leading options: hand them over untouched
            return cmd_bench(argparse.Namespace(bench_args=argv[1:]))
        parser = build_parser()
        args = parser.parse_args(argv)
        if args.version:
            import lazyground

            print(f"lazyground {lazyground.__version__}")
            return EXIT_OK
        if args.command is None:
            parser.print_help()
            return EXIT_BAD_INPUT
        return COMMANDS[args.command](args)
    except (UsageError, SceneError, GroundingError) as exc:
        if debug:
            traceback.print_exc()
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except BrokenPipeError:  # the reader closed our output (`| head`): nothing more to say, to anyone
        _silence_stdout()
        return EXIT_PIPE_CLOSED
    except Exception as exc:  # a bug: one line unless --debug
        if _interrupted(exc):
            print("interrupted", file=sys.stderr)
            return EXIT_INTERRUPTED
        if debug:
            traceback.print_exc()
        print(f"internal error: {type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''} (rerun with --debug)", file=sys.stderr)
        return EXIT_INTERNAL


if __name__ == "__main__":
    sys.exit(main())
