"""One benchmark run as a plain function, and the executors that fan runs out.

:func:`run` turns a :class:`RunSpec` into one CSV row (a dict). It is the
same function whether it runs in a local process pool (:func:`run_local`,
each worker loads every scene's DrakeWorld once, in its initializer, and
reuses it) or on a Dask cluster (:func:`run_cluster`, worlds are loaded on
first use in each worker). Rows come back as runs finish, so the caller can
write them at once and keep them when interrupted.
"""

from __future__ import annotations

import functools
import signal
import time
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass
from typing import Callable, Iterable, Iterator

import numpy as np

from lazyground.bench import arms, families
from lazyground.bench.baselines import parse_planner
from lazyground.bench.sscbirrt_peer import PLANNER
from lazyground.planning.problem import PlanStatus, RegionStats, proven_unreachable
from lazyground.settings import Algorithm

LAZYGROUND = "lazyground"
ALGORITHMS = {Algorithm.RRT: LAZYGROUND, Algorithm.BIDIRECTIONAL: "lazyground-bidirectional"}  # algorithm -> planner column
SSCBIRRT = PLANNER  # sscbirrt's CBiRRT (the module imports sscbirrt only when a run needs it)
PEERS = ("ompl-RRT", "ompl-RRTConnect", SSCBIRRT)

FIELDS = (
    "scene", "planner", "strategy", "bias", "seed", "status", "time_s", "grounding_s", "goal_sampling_s",
    "collision_s", "other_s", "iterations", "tree_size", "goal_samples", "resamplings", "interpretation",
    "region", "path_length", "time_limit", "message",
    "raw_path_length", "shortcut_s", "timing_s", "duration_s",  # after the solve (lazyground.motion; #16)
    "direct_path_length",  # start to goal in a straight line: the shortened length's lower bound (#16)
    "collision_checks",  # the planner's own checks (#19)
    "goal_attempts",  # goal-sampling attempts over all regions, failed ones included (#19)
    "objective", "budget",  # first / shortest / fastest and the seconds after the first solution (#30)
    "total_s",  # api.plan's wall time less world set-up: grounding, search, shortening and timing (#30)
    "max_sweep",  # rad: the most any revolute joint turns away from its start along the final path (#30)
    "reach_prior", "proven_unreachable",  # the setting, and the interpretations it dropped (car scenes, #33)
)


@dataclass(frozen=True)
class RunSpec:
    """One run: a scene (file path or ``arm:<dof>``), a planner configuration and a seed."""

    scene: str
    planner: str  # one of ALGORITHMS' values (ours) or of PEERS
    strategy: str  # lazyground: a strategy name; peers: "goal-states"
    bias: float | None  # goal bias; None for RRTConnect (it has none)
    seed: int
    time_limit: float
    request: str | None = None  # None: the scene's first expectation's request
    kinematics: str | None = None  # car scenes: None keeps the scene's (a results file holds one mode)
    objective: str = "first"  # lazyground: which solution is returned (#30)
    budget: float | None = None  # objective shortest/fastest: seconds after the first solution (None: its time)
    reach_prior: bool = True  # car scenes: drop the goal regions the reach prior proves unreachable (every method)

    def key(self) -> tuple:
        """What identifies a run in a results file (for --resume)."""
        return (self.scene_name, self.planner, self.strategy, _fmt_bias(self.bias), str(self.seed), str(self.objective))

    @property
    def scene_name(self) -> str:
        dof = arms.parse_arm_key(self.scene)
        if dof is not None:
            return f"arm_{dof}"
        if self.scene.split(":")[0] in families.FAMILIES:
            return self.scene.replace(":", "_")
        from pathlib import Path

        return Path(self.scene).stem


def _fmt_bias(b) -> str:
    return "" if b is None or b == "" else f"{float(b):g}"


def row_key(row: dict) -> tuple:
    return (row["scene"], row["planner"], row["strategy"], _fmt_bias(row["bias"]), str(row["seed"]),
            str(row.get("objective") or "first"))


@dataclass
class Problem:
    """A loaded benchmark problem: the scene, its Drake world and how to get goal regions."""

    name: str
    scene: object
    world: object
    request: str | None
    regions: tuple = ()  # fixed C-space regions (generated arms); empty: ground the request

    def ground(self):
        """(goal regions, grounding seconds)."""
        if self.regions:
            return self.regions, 0.0
        import grounding

        t0 = time.perf_counter()
        g = grounding.ground(self.request, self.scene)
        return g.goal_regions, time.perf_counter() - t0


PROBLEM_CACHE_SIZE = 16  # scene keys kept per process: more than any one bench run sweeps (Table II: 3, DOF sweep: 5)


@functools.lru_cache(maxsize=PROBLEM_CACHE_SIZE)
def load_problem(key: str) -> Problem:
    """The problem for a scene key (a scene file or ``arm:<dof>``), built once per process and cached by the key."""
    from lazyground.drake.world import DrakeWorld

    dof = arms.parse_arm_key(key)
    if dof is not None:
        scene = arms.arm_scene(dof)
        world = DrakeWorld(scene, visual=False)
        problem = Problem(scene.name, scene, world, None, arms.goal_regions(dof, world.config_free))
    else:
        from lazyground.scene import load_scene

        scene = families.load_family_scene(key) if families.parse_key(key) is not None else load_scene(key)
        request = scene.expect[0].request if scene.expect else None
        problem = Problem(scene.name, scene, DrakeWorld(scene, visual=False), request)
    return problem


def init_worker(scene_keys: Iterable[str]) -> None:
    """Process-pool initializer: load each scene's world once; Ctrl-C is the parent's business."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for key in scene_keys:
        try:
            load_problem(key)
        except Exception:  # reported per run by run()
            pass


def run(spec: RunSpec) -> dict:
    """Run one benchmark configuration; never raises (failures become status "error")."""
    row = {f: "" for f in FIELDS}
    row.update(scene=spec.scene_name, planner=spec.planner, strategy=spec.strategy, bias=_fmt_bias(spec.bias),
               seed=spec.seed, time_limit=spec.time_limit, objective=spec.objective,
               budget="" if spec.budget is None else spec.budget, reach_prior=spec.reach_prior)
    try:
        problem = load_problem(spec.scene)
        if spec.request is not None and not problem.regions:
            problem = Problem(problem.name, problem.scene, problem.world, spec.request)
        if problem.request is None and not problem.regions:
            raise ValueError(f"scene {problem.name} has no expect: request; give --request")
        if spec.planner in ALGORITHMS.values():
            row.update(_run_lazyground(problem, spec))
        elif parse_planner(spec.planner) is not None:
            row.update(_run_baseline(problem, spec))
        elif spec.planner == SSCBIRRT:
            from lazyground.bench.sscbirrt_peer import run_peer

            row.update(run_peer(problem, spec))
        else:
            from lazyground.bench.ompl_peer import run_peer

            row.update(run_peer(problem, spec))
    except Exception as exc:  # a benchmark keeps going; the row says why this run failed
        text = str(exc).strip().splitlines()
        row.update(status="error", message=f"{type(exc).__name__}: {text[0] if text else ''}")
    return row


def _run_lazyground(problem: Problem, spec: RunSpec) -> dict:
    algorithm = next(a for a, name in ALGORITHMS.items() if name == spec.planner)
    overrides = dict(strategy=spec.strategy, algorithm=algorithm, goal_bias=spec.bias, time_limit=spec.time_limit,
                     kinematics=spec.kinematics, reach_prior=spec.reach_prior)
    if problem.regions:  # generated arm: C-space regions, no grounding
        from lazyground.api import planner_settings
        from lazyground.goals import ConfigGoalSource
        from lazyground.planning import solve

        settings = planner_settings(problem.scene, edge_resolution=arms.EDGE_RESOLUTION, **overrides)
        world = problem.world
        source = ConfigGoalSource(problem.regions, world.space, world)
        result = solve(world.space, world, source, world.start, settings, np.random.default_rng(spec.seed), seed=spec.seed)
        region = result.goal_region
        return result_fields(result, 0.0, region.interpretation if region else "", region.id if region else "")
    from lazyground import api

    report = api.plan(problem.scene, problem.request, seed=spec.seed, world=problem.world, objective=spec.objective,
                      budget=spec.budget, **overrides)
    region = report.result.goal_region
    fields = result_fields(report.result, report.grounding_s, report.chosen.id if report.chosen else "", region.id if region else "")
    fields["total_s"] = report.total_s
    return fields | motion_fields(report.motion) | sweep_field(report.motion, problem.world)


def _run_baseline(problem: Problem, spec: RunSpec) -> dict:
    """A baseline of :mod:`lazyground.bench.baselines` on the same world, goal sampler and clock as ours."""
    from lazyground.api import run_settings
    from lazyground.bench.baselines import run_baseline
    from lazyground.goals import reach_prior_drops
    from lazyground.tasks.car_space import planning_space

    name, bidirectional = parse_planner(spec.planner)
    algorithm = Algorithm.BIDIRECTIONAL if bidirectional else Algorithm.RRT
    chosen = run_settings(problem.scene, strategy=spec.strategy, algorithm=algorithm, goal_bias=spec.bias,
                          time_limit=spec.time_limit, kinematics=spec.kinematics, reach_prior=spec.reach_prior)
    settings = chosen.planner
    regions, grounding_s = problem.ground()
    world = problem.world
    space = planning_space(problem.scene, world.space, settings.kinematics)
    result, seconds, iterations, attempts = run_baseline(name, problem.scene, world, regions, space, settings, spec.seed,
                                                         sampling=chosen.goal_sampling)
    if result is None:
        return dict(status=PlanStatus.TIMEOUT.value, time_s=grounding_s + seconds, grounding_s=grounding_s,
                    message="no planner call within the time limit")
    region = result.goal_region
    fields = result_fields(result, grounding_s, region.interpretation if region else "", region.id if region else "")
    dropped = reach_prior_drops(regions, world, chosen.goal_sampling)  # over every region, not the last call's
    proven = proven_unreachable(regions, [RegionStats(unreachable=dropped.get(j, "")) for j in range(len(regions))])[0]
    # the whole method's time and work, not only the call that ended it
    return fields | dict(time_s=grounding_s + seconds, iterations=iterations, goal_attempts=attempts,
                         other_s=max(0.0, seconds - result.goal_sampling_s - result.collision_s), proven_unreachable=proven)


def motion_fields(motion) -> dict:
    """The CSV fields of a plan's shortcut and trajectory (empty when there is none)."""
    if motion is None:
        return {}
    return dict(raw_path_length=motion.raw_length, direct_path_length=motion.direct_length,
                shortcut_s=motion.shortcut_s, timing_s=motion.timing_s,
                duration_s=motion.trajectory.duration if motion.trajectory is not None else "")


def sweep_field(motion, world) -> dict:
    """``max_sweep``: the most a revolute joint turns from its start along the shortened path (empty without one)."""
    turns = getattr(getattr(world, "coordinates", None), "turns", None)
    if motion is None or motion.shortcut is None or turns is None or not np.any(turns):
        return {}
    from lazyground.planning.turns import sweeps

    return dict(max_sweep=float(np.max(sweeps(motion.shortcut.path, world.space.wrap)[np.asarray(turns, bool)])))


def result_fields(result, grounding_s: float, interpretation: str, region: str) -> dict:
    """The CSV fields of a PlanResult; time_s includes grounding, as a user experiences it."""
    return dict(
        status=result.status.value,
        time_s=grounding_s + result.time_s,
        grounding_s=grounding_s,
        goal_sampling_s=result.goal_sampling_s,
        collision_s=result.collision_s,
        other_s=result.other_s,
        iterations=result.iterations,
        tree_size=result.tree_size,
        goal_samples=len(result.goal_samples),
        resamplings=result.resamplings,
        interpretation=interpretation,
        region=region,
        path_length=result.path_length,
        message=result.message,
        collision_checks=result.collision_checks,
        goal_attempts=sum(st.attempts for st in result.region_stats),
        proven_unreachable=proven_unreachable(result.regions, result.region_stats)[0],
    )


# --- executors ------------------------------------------------------------------------------

def run_local(specs: list[RunSpec], jobs: int) -> Iterator[dict]:
    """Rows in completion order from a pool of ``jobs`` worker processes.

    Closing the generator early (e.g. on KeyboardInterrupt in the consumer)
    cancels the pending runs and stops the workers.
    """
    keys = sorted({s.scene for s in specs})
    pool = ProcessPoolExecutor(max_workers=max(1, jobs), initializer=init_worker, initargs=(keys,))
    pending = set()
    try:
        queue = iter(specs)
        # Keep a bounded number of runs in flight so an interrupt has little to cancel.
        for spec in queue:
            pending.add(pool.submit(run, spec))
            if len(pending) >= 4 * jobs:
                break
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                yield fut.result()
                nxt = next(queue, None)
                if nxt is not None:
                    pending.add(pool.submit(run, nxt))
    finally:
        if pending:  # interrupted: drop what is queued, stop the workers we started
            for fut in pending:
                fut.cancel()
            for proc in list(getattr(pool, "_processes", {}).values()):
                proc.terminate()
        pool.shutdown(wait=True, cancel_futures=True)


def run_cluster(specs: list[RunSpec], address) -> Iterator[dict]:
    """Rows in completion order from an existing Dask distributed scheduler.

    Args:
        address: the scheduler address (``tcp://host:8786``) or a ``distributed.Client``.

    Raises:
        ImportError: dask.distributed is not installed (``pip install .[cluster]``).
    """
    from dask.distributed import Client, as_completed

    client = address if isinstance(address, Client) else Client(address)
    futures = client.map(run, specs, pure=False)
    try:
        for fut in as_completed(futures):
            yield fut.result()
    finally:
        client.cancel([f for f in futures if not f.done()])
        if client is not address:
            client.close()


class Progress:
    """A one-line progress bar with an ETA on a stream (stderr)."""

    def __init__(self, total: int, stream, width: int = 30):
        self.total, self.stream, self.width = total, stream, width
        self.done = self.solved = 0
        self.t0 = self._last = time.perf_counter()
        self._tty = bool(getattr(stream, "isatty", lambda: False)())

    def update(self, row: dict) -> None:
        self.done += 1
        self.solved += row.get("status") == "solved"
        elapsed = time.perf_counter() - self.t0
        eta = elapsed / self.done * (self.total - self.done)
        fill = int(self.width * self.done / max(1, self.total))
        bar = "#" * fill + "." * (self.width - fill)
        text = f"[{bar}] {self.done}/{self.total} ({self.solved} solved) elapsed {_hms(elapsed)} ETA {_hms(eta)}"
        if self._tty:
            self.stream.write("\r" + text + " ")
        elif self.done == self.total or time.perf_counter() - self._last > 10.0:  # logs: a line every 10 s
            self.stream.write(text + "\n")
            self._last = time.perf_counter()
        self.stream.flush()

    def close(self) -> None:
        if self._tty:
            self.stream.write("\n")
        self.stream.flush()


def _hms(s: float) -> str:
    s = int(round(s))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}"


def execute(specs: list[RunSpec], on_row: Callable[[dict], None], jobs: int = 1, cluster=None) -> None:
    """Run every spec locally or on a cluster, calling ``on_row`` as each finishes."""
    rows = run_cluster(specs, cluster) if cluster is not None else run_local(specs, jobs)
    try:
        for row in rows:
            on_row(row)
    finally:
        rows.close()

