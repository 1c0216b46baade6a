"""``lazyground bench``: scenes x strategies x goal bias x seeds, in parallel, with the paper's tables.

    lazyground bench --table 1 --runs 20 --out bench_t1
    lazyground bench --table 2 --runs 5 --peers --jobs 2
    lazyground bench --table 2 --algorithms rrt,bidirectional --runs 10
    lazyground bench --scenes parking_1,arm:8 --strategies reward-penalty --biases 0.05,0.5 --runs 50
    lazyground bench --dof-sweep --runs 10
    lazyground bench --nn-scaling
    lazyground bench --table 1 --cluster tcp://scheduler:8786

Writes into ``--out``: results.csv (every run, written as it finishes),
table.md (the paper's layout + where the time goes), boxplots.png,
ompl_<scene>.log (OMPL benchmark logs) and, for the sweep, dof_sweep.png.
Ctrl-C keeps the finished runs, writes the outputs from them and exits 130.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

from lazyground.bench import arms, families
from lazyground.bench.baselines import BASELINES, parse_planner, planner_name
from lazyground.bundled import bundled_scene, scene_names as bundled_names
from lazyground.bench.runner import ALGORITHMS, FIELDS, RunSpec, execute, row_key, Progress
from lazyground.settings import BY_NAME, Algorithm, Kinematics, Strategy, from_scene

ALL_STRATEGIES = (Strategy.CONSECUTIVE, Strategy.RANDOM, Strategy.REWARD_PENALTY)  # the tables' column order
TABLES = {
    1: dict(scenes=("parking_1", "parking_2"), strategies=ALL_STRATEGIES, biases=(0.05,), runs=1000,
            title="Table I: parking, computation time (s)"),
    2: dict(scenes=("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3"), strategies=(Strategy.CONSECUTIVE, Strategy.REWARD_PENALTY),
            biases=(0.05, 0.5), runs=100, title="Table II: Fetch, computation time (s)",
            requests={"fetch_cans_1": "pick up a can", "fetch_cans_2": "pick up a can", "fetch_boxes_3": "pick up a box"}),
}
EXIT_OK, EXIT_BAD_INPUT, EXIT_INTERRUPTED = 0, 2, 130
PLOT_DPI = 60  # --plot: small PNGs to commit beside benchmarks/RESULTS.md


class BenchUsageError(Exception):
    """Bad bench arguments (exit 2, one line)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise BenchUsageError(message)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="lazyground bench", description="Benchmark goal-selection strategies (and OMPL / sscbirrt peers).")
    p.add_argument("--table", type=int, choices=sorted(TABLES), help="the paper's Table I (parking) or II (Fetch)")
    p.add_argument("--dof-sweep", action="store_true", help=f"generated planar arms of {', '.join(map(str, arms.DOFS))} DOF")
    p.add_argument("--family-sweep", metavar="NAMES", help="comma list of generated sweeps (issue #33): lot, lot-fixed, rack-panda, rack-fetch, "
                   "lot-fraction; time to the first solution against N (family_sweep.png)")
    p.add_argument("--sizes", help="--family-sweep: the sizes (N, or k for lot-fraction) instead of the sweep's own")
    p.add_argument("--nn-scaling", action="store_true", help="time per iteration from 1,000 to 100,000 tree nodes")
    p.add_argument("--iteration-profile", action="store_true", help="where a search iteration's time goes (nearest "
                   "neighbours, steering, checks, bookkeeping) on --scenes (default: the three Fetch scenes), --runs seeds "
                   "(default 10), in this process")
    p.add_argument("--scenes", help="comma list: scene files, names in yaml_scenes/, arm:<dof>, or generated families "
                   "lot:<free>:<reachable>[:<seed>] and rack:<panda|fetch>:<objects>:<reachable>[:<seed>]")
    p.add_argument("--strategies", help=f"comma list of {BY_NAME['strategy'].allowed()}")
    p.add_argument("--biases", help=f"comma list of goal biases in {BY_NAME['goal_bias'].allowed()}")
    p.add_argument("--algorithms", help=f"comma list of {BY_NAME['algorithm'].allowed()} (default: rrt, the paper's Algorithm 1)")
    p.add_argument("--objectives", help=f"comma list of {BY_NAME['objective'].allowed()} (default: first; #30)")
    p.add_argument("--budget", type=float, help="seconds shortest / fastest keep planning after the first solution "
                   "(default: the first solution's time)")
    p.add_argument("--runs", type=int, help="seeds per configuration (tables: 1000 / 100; otherwise 10)")
    p.add_argument("--time-limit", type=float, help="seconds per run (default: each scene's; arms 10)")
    p.add_argument("--request", help="the request (default: each scene's first expectation)")
    p.add_argument("--kinematics", choices=BY_NAME["kinematics"].choices, help="car scenes: holonomic (the paper's), reeds-shepp or dubins "
                   "(default: each scene's)")
    p.add_argument("--baselines", help="comma list of what users do instead (issue #33), each on every --algorithms planner: "
                   "nearest-first, multiplexer, eager, independent (see lazyground/bench/baselines.py)")
    p.add_argument("--baseline-time-limit", type=float, help="--baselines: seconds per baseline run (default: --time-limit), "
                   "so that their unsolved runs do not cap the ratios to ours (reported as bounds in table.md)")
    p.add_argument("--no-reach-prior", action="store_true", help="car scenes: sample every goal region, also those "
                   "the reach prior proves unreachable (setting reach_prior: false; every method, baselines included)")
    p.add_argument("--peers", action="store_true", help="also run OMPL RRT and RRTConnect and sscbirrt's CBiRRT (pip install .[bench])")
    p.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="worker processes (default: cores)")
    p.add_argument("--cluster", metavar="ADDRESS", help="run on this Dask scheduler instead (pip install .[cluster])")
    p.add_argument("--seed", type=int, default=0, help="first seed (runs use seed, seed+1, ...)")
    p.add_argument("--out", default="bench_output", help="output folder (default: bench_output)")
    p.add_argument("--resume", action="store_true", help="keep results.csv in --out and skip the runs it holds")
    p.add_argument("--plot", metavar="FILE.png", help="also write a small plot for docs: the box plots, the DOF sweep's "
                   "curve, or (--nn-scaling alone) time per iteration against tree size")
    p.add_argument("--debug", action="store_true")
    return p


def _csv_list(text: str | None, default) -> list[str]:
    return [t.strip() for t in text.split(",") if t.strip()] if text else list(default)


def _checked(option: str, setting: str, values: list) -> list:
    """``values`` of a sweep option, each checked and converted by the setting's declaration."""
    try:
        return [BY_NAME[setting].coerce(v) for v in values]
    except ValueError as exc:
        raise BenchUsageError(f"--{option}: {str(exc).partition(': ')[2]}") from None


def resolve_scene(name: str) -> str | None:
    """A scene key: ``arm:<dof>``, a file path, or a name in yaml_scenes/; None when missing."""
    if arms.parse_arm_key(name) is not None:
        return name
    try:
        if families.parse_key(name) is not None:
            return name
    except ValueError as exc:
        raise BenchUsageError(f"--scenes: {exc}") from None
    if Path(name).is_file():
        return name
    bundled = bundled_scene(name)  # a bare name, from any directory (installed or source tree)
    return str(bundled) if bundled is not None else None


def plan_specs(args) -> tuple[list[RunSpec], list[str], str]:
    """(runs in order, notes, title) from the arguments."""
    notes: list[str] = []
    preset = TABLES.get(args.table, {})
    if args.dof_sweep:
        preset = dict(scenes=tuple(arms.arm_key(d) for d in arms.DOFS), strategies=ALL_STRATEGIES, biases=(0.05,), runs=10,
                      title="Generated planar arms: time (s) against DOF")
    if getattr(args, "family_sweep", None):
        from lazyground.bench.sweep import sweep_keys

        try:
            sizes = [int(n) for n in _csv_list(args.sizes, ())]
            keys = [k for name in _csv_list(args.family_sweep, ()) for k in sweep_keys(name, sizes)]
        except ValueError as exc:
            raise BenchUsageError(f"--family-sweep / --sizes: {exc}") from None
        preset = dict(preset, scenes=tuple(keys), title="Time to the first solution against the number of interpretations")
    scene_names = _csv_list(args.scenes, preset.get("scenes", ("parking_1",)))
    strategies = _checked("strategies", "strategy", _csv_list(args.strategies, preset.get("strategies", ALL_STRATEGIES)))
    try:
        biases = [float(b) for b in _csv_list(args.biases, preset.get("biases", (0.05,)))]
    except ValueError:
        raise BenchUsageError(f"--biases: not a list of numbers: {args.biases!r}") from None
    biases = _checked("biases", "goal_bias", biases)
    runs = args.runs if args.runs is not None else preset.get("runs", 10)
    if runs < 1:
        raise BenchUsageError("--runs must be >= 1")
    if args.time_limit is not None:
        _checked("time-limit", "time_limit", [args.time_limit])
    baseline_limit = getattr(args, "baseline_time_limit", None)  # absent from Namespaces built by hand (tests)
    if baseline_limit is not None:
        _checked("baseline-time-limit", "time_limit", [baseline_limit])
    _checked("seed", "seed", [args.seed])
    keys, missing = [], []
    for name in scene_names:
        key = resolve_scene(name)
        (keys if key else missing).append(key or name)
    if missing:
        notes.append(f"missing scenes (neither files nor bundled scenes: {', '.join(bundled_names())}): {', '.join(missing)}")
    if not keys:
        raise BenchUsageError(f"no scene to run: {notes[0]}")
    for key in keys:  # bad input is one line now, not an error row in every run
        _check_request(key, args.request or preset.get("requests", {}).get(Path(key).stem))
    algorithms = _checked("algorithms", "algorithm", _csv_list(args.algorithms, preset.get("algorithms", (Algorithm.RRT,))))
    objectives = _checked("objectives", "objective", _csv_list(getattr(args, "objectives", None), ("first",)))
    budget = getattr(args, "budget", None)
    if budget is not None:
        _checked("budget", "budget", [budget])
    configs = [(ALGORITHMS[a], s, b, o) for a in algorithms for b in biases for s in strategies for o in objectives]
    for name in _csv_list(getattr(args, "baselines", None), ()):
        if name not in BASELINES:
            raise BenchUsageError(f"--baselines: unknown {name!r} (known: {', '.join(BASELINES)})")
        configs += [(planner_name(name, a is Algorithm.BIDIRECTIONAL), Strategy.CONSECUTIVE.value, b, "first")
                    for a in algorithms for b in biases]
    kinematics = getattr(args, "kinematics", None)  # absent from Namespaces built by hand (tests)
    if args.peers and kinematics not in (None, Kinematics.HOLONOMIC):
        raise BenchUsageError("--peers plan holonomic paths only; leave out --kinematics or --peers")
    if args.peers:
        from lazyground.bench import ompl_peer, sscbirrt_peer

        if ompl_peer.ompl_available():
            configs += [("ompl-RRT", "goal-states", b, "first") for b in biases] + [("ompl-RRTConnect", "goal-states", None, "first")]
        else:
            notes.append(ompl_peer.MISSING)
        if sscbirrt_peer.sscbirrt_available():
            configs.append((sscbirrt_peer.PLANNER, "goal-states", None, "first"))
        else:
            notes.append(sscbirrt_peer.MISSING)
    reach_prior = not getattr(args, "no_reach_prior", False)  # absent from Namespaces built by hand (tests)
    specs = []
    for i in range(runs):  # seeds outermost: an interrupted run still covers every configuration
        for key in keys:
            limit = args.time_limit if args.time_limit is not None else _scene_time_limit(key)
            request = args.request or preset.get("requests", {}).get(Path(key).stem)
            for planner, strategy, bias, objective in configs:
                own = baseline_limit if baseline_limit is not None and parse_planner(planner) is not None else limit
                specs.append(RunSpec(key, planner, strategy, bias, args.seed + i, own, request, kinematics,
                                     str(objective), budget if objective != "first" else None, reach_prior))
    return specs, notes, preset.get("title", "Computation time (s)")


def _check_request(key: str, request: str | None) -> None:
    """A generated arm with at least one joint; a scene with a request (given or its first expectation's)
    that grounds in it."""
    dof = arms.parse_arm_key(key)
    if dof is not None:
        if dof < 1:
            raise BenchUsageError(f"--scenes {key}: an arm needs at least one joint")
        return
    import grounding
    from grounding.model import GroundingError
    from lazyground.scene import load_scene

    scene = families.load_family_scene(key) if families.parse_key(key) is not None else load_scene(key)
    try:
        from_scene(scene.planner)
    except ValueError as exc:
        raise BenchUsageError(f"scene {scene.name}: {exc}") from None
    request = request or (scene.expect[0].request if scene.expect else None)
    if request is None:
        raise BenchUsageError(f"scene {scene.name} has no expect: request; give --request")
    try:
        grounding.ground(request, scene)
    except GroundingError as exc:
        raise BenchUsageError(f"request {request!r} on scene {scene.name}: {exc}") from None


def _scene_time_limit(key: str) -> float:
    if arms.parse_arm_key(key) is not None:
        return 10.0
    if families.parse_key(key) is not None:
        return families.load_family_scene(key).planner.time_limit
    from lazyground.scene import load_scene

    return load_scene(key).planner.time_limit


def main(argv: list[str]) -> int:
    debug = "--debug" in argv
    try:
        return _main(build_parser().parse_args(argv))
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:
        from grounding.model import GroundingError
        from lazyground.typed_yaml import SceneError

        if debug or not isinstance(exc, (BenchUsageError, SceneError, GroundingError, ImportError)):
            raise
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT


def _main(args) -> int:
    if args.jobs < 1:
        raise BenchUsageError(f"--jobs must be >= 1, got {args.jobs}")
    from lazyground.outputs import folder_problem

    out = Path(args.out)
    problem = folder_problem(out)
    if problem:
        raise BenchUsageError(f"--out {args.out}: {problem}")
    if args.plot and (Path(args.plot).suffix.lower() != ".png" or folder_problem(Path(args.plot).resolve().parent)):
        raise BenchUsageError(f"--plot {args.plot}: must be a .png file in a writable folder")
    if args.nn_scaling:
        from lazyground.bench import nn_scaling

        scaling = nn_scaling.measure()
        text = nn_scaling.report(scaling)
        (out / "nn_scaling.md").write_text(text)
        print(text, end="")
        if not (args.table or args.dof_sweep or args.scenes):
            if args.plot:
                nn_scaling.plot(scaling, args.plot, dpi=PLOT_DPI)
                print(f"wrote {args.plot}", file=sys.stderr)
            return EXIT_OK
    if args.iteration_profile:
        return _iteration_profile(args, out)
    specs, notes, title = plan_specs(args)
    for note in notes:
        print(f"note: {note}", file=sys.stderr)
    from lazyground.bench.tables import CsvSink, read_csv

    csv_path = out / "results.csv"
    if args.resume and csv_path.is_file():
        done = {row_key(r) for r in _resumable(csv_path)}
        specs = [s for s in specs if s.key() not in done]
        print(f"resume: {len(done)} runs in {csv_path}, {len(specs)} to go", file=sys.stderr)
    cluster = args.cluster
    if cluster is not None:
        try:
            import distributed  # noqa: F401
        except ImportError:
            raise BenchUsageError("--cluster needs Dask distributed: pip install .[cluster]") from None
    where = f"cluster {cluster}" if cluster else f"{args.jobs} worker process(es)"
    print(f"{len(specs)} runs on {where}; results in {csv_path}", file=sys.stderr)
    sink = CsvSink(csv_path, append=args.resume)
    progress = Progress(len(specs), sys.stderr)
    t0 = time.perf_counter()
    interrupted = False

    def on_row(row):
        if row["status"] == "interrupted":
            return
        sink.write(row)
        progress.update(row)

    try:
        execute(specs, on_row, jobs=args.jobs, cluster=cluster)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        sink.close()
        progress.close()
    rows = [r for r in read_csv(csv_path) if r["status"] != "interrupted"]
    write_outputs(rows, out, title, notes, time.perf_counter() - t0, dof_sweep=args.dof_sweep)
    if args.plot and rows:
        from lazyground.bench import tables

        (tables.dof_plot if args.dof_sweep else tables.box_plots)(rows, args.plot, dpi=PLOT_DPI)
        print(f"wrote {args.plot}", file=sys.stderr)
    errors = [r for r in rows if r["status"] == "error"]
    if errors:
        print(f"warning: {len(errors)} run(s) failed, e.g. {errors[0]['scene']}: {errors[0]['message']}", file=sys.stderr)
    if interrupted:
        print(f"interrupted: kept {progress.done} finished run(s) in {csv_path}", file=sys.stderr)
        return EXIT_INTERRUPTED
    return EXIT_OK


def _iteration_profile(args, out: Path) -> int:
    from lazyground.bench import iteration_profile

    keys = _csv_list(args.scenes, ["fetch_cans_1", "fetch_cans_2", "fetch_boxes_3"])
    seeds = range(args.seed, args.seed + (args.runs or 10))
    profiles = []
    for key in keys:
        overrides = {} if args.time_limit is None else {"time_limit": args.time_limit}
        profiles.append(iteration_profile.profile_scene(resolve_scene(key) or key, seeds, args.request, **overrides))
        print(f"profiled {key}", file=sys.stderr)
    text = iteration_profile.report(profiles)
    (out / "iteration_profile.md").write_text(text)
    print(text, end="")
    return EXIT_OK


def _resumable(path: Path) -> list[dict]:
    """The rows of a results.csv to resume; one with other columns (another version's, or not ours) is refused:
    new rows appended under its header would land in the wrong columns."""
    import csv

    from lazyground.bench.tables import read_csv

    try:
        with open(path, newline="", encoding="utf-8") as f:
            header = next(csv.reader(f), [])
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        raise BenchUsageError(f"--resume: cannot read {path}: {exc}") from None
    if header and header != list(FIELDS):
        raise BenchUsageError(f"--resume: {path} has other columns than this version of lazyground bench writes; "
                              "give another --out, or leave out --resume to start it again")
    return read_csv(path)


def write_outputs(rows: list[dict], out: Path, title: str, notes: list[str], total_s: float, dof_sweep: bool = False) -> None:
    """table.md, boxplots.png, ompl_<scene>.log (and dof_sweep.png) from the finished rows."""
    from lazyground.bench import ompl_log, tables

    md = [tables.markdown_table(rows, f"## {title}"), "## Where the time goes (every finished run, mean seconds)\n", tables.time_split_table(rows)]
    if len({r["strategy"] for r in rows if r["planner"].startswith("lazyground")}) > 1:
        from lazyground.bench.compare import strategy_table

        md += ["## Strategies against consecutive (Mann-Whitney U, two-sided)\n", strategy_table(rows)]
    from lazyground.bench.sweep import size_of, sweep_plot, sweep_ratios, sweep_table, sweep_tests

    family = [r for r in rows if size_of(r["scene"]) is not None]
    if family:
        md += ["## Against the number of interpretations (generated families)\n", sweep_table(family),
               "## Each method against round-robin per size (Mann-Whitney U, two-sided and one-sided; layouts pooled)\n",
               sweep_tests(family)]
        ratios = sweep_ratios(family)
        if ratios:
            md += ["## Baselines against ours per size (median s; >= where unsolved runs censor a median)\n", ratios]
    objectives = tables.objective_table(rows)
    if objectives:
        md += ["## Objectives: path length, joint sweep and time against first (#30)\n", objectives]
    motion = tables.motion_table(rows)
    if motion:
        md += ["## Shortening and timing after the solve (solved runs, medians)\n", motion]
    md += [f"Note: {n}\n" for n in notes]
    (out / "table.md").write_text("\n".join(md))
    print("\n".join(md))
    if not rows:
        return
    tables.box_plots(rows, out / "boxplots.png")
    if dof_sweep:
        tables.dof_plot(rows, out / "dof_sweep.png")
    if family:
        sweep_plot(family, out / "family_sweep.png")
    for scene in tables.scenes_of(rows):
        srows = [r for r in rows if r["scene"] == scene]
        limit = max(float(r["time_limit"]) for r in srows)
        setup = f"lazyground bench: scene {scene}; times include grounding and goal sampling"
        ompl_log.write_log(out / f"ompl_{scene}.log", scene, srows, limit, total_s, setup)
    print(f"wrote {out}/: results.csv, table.md, boxplots.png, ompl_<scene>.log" + (", dof_sweep.png" if dof_sweep else ""), file=sys.stderr)
