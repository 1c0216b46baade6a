"""Seeded stress test: plan many times across the bundled scenes; no invalid path, no unexpected exception.

    python3 tools/stress.py                      # $LAZYGROUND_STRESS_RUNS runs (default 40)
    python3 tools/stress.py --runs 1000 --jobs 2 --out stress.json

Every run varies the scene, seed, planner, goal-selection strategy and goal bias
(drawn from ``--seed``, so the list of runs is reproducible). Every solved
path is re-checked at a tenth of the planner's edge resolution
(``path_is_valid`` in the space it was planned in: a car's along its curves); pick-and-place reports are re-checked with
``validate_pick_and_place`` (the carried object included). Every solved plan's
timed trajectory (issue #16) is re-checked too: its ends, the curve between
its samples at the same resolution, and its velocity and acceleration limits
(``lazyground.motion.validate``). Any exception other
than a planning status is counted as unexpected. Prints the figures: runs,
solved, invalid paths found, unexpected exceptions and the largest time-limit
overshoot (reported planning time / limit - 1). Exit 1 when a path is invalid
or an exception escaped. tests/reliability/test_stress.py runs this in CI.
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))

from lazyground.settings import Algorithm, Strategy  # noqa: E402
from lazyground.tolerance import accepted_error  # noqa: E402

STRATEGIES = tuple(Strategy)
BIASES = (0.05, 0.1, 0.2, 0.5)
ALGORITHMS = tuple(Algorithm)  # both planners on every scene, each with the scene's settings for it
PARKING_LIMIT = 5.0  # s: parking solves in 1-2 s; the cap keeps a rare slow run short
FETCH_LIMITS = {"pick": 2.0, "place": 3.0}  # s: short on purpose; timeouts are fine, invalid paths are not
PARKING_SHARE = 0.85
GOAL_TOLERANCE = max(0.01, *accepted_error())  # m / rad: at least what IK accepts (0.011 rad); a path's end must lie in its region within this
FALLBACK_REQUESTS = {"fetch_cans_1": "pick up a can", "fetch_cans_2": "pick up a can", "fetch_boxes_3": "pick up a box"}
DEFAULT_RUNS = int(os.environ.get("LAZYGROUND_STRESS_RUNS", "40"))


@dataclass(frozen=True)
class StressRun:
    """One planning query of the stress test."""

    index: int
    scene: str  # file stem in yaml_scenes/
    request: str
    seed: int
    strategy: str
    goal_bias: float
    time_limit: float
    algorithm: str = Algorithm.RRT


def bundled_scenes() -> tuple[list[tuple[str, str]], list[tuple[str, str]], list[str]]:
    """(parking scenes, robot-arm scenes) as (name, request), and notes on scenes skipped."""
    from lazyground.scene import SceneError, load_scene

    parking, arm, notes = [], [], []
    for path in sorted((REPO / "yaml_scenes").glob("*.yaml")):
        try:
            scene = load_scene(path)
        except SceneError as exc:  # a scene being edited elsewhere: say so, do not fail here
            notes.append(f"skipped {path.name}: {exc}")
            continue
        request = scene.expect[0].request if scene.expect else FALLBACK_REQUESTS.get(path.stem)
        if request is None:
            notes.append(f"skipped {path.name}: no request to plan")
        elif path.stem.startswith("parking"):
            parking.append((path.stem, request))
        elif path.stem.startswith(("fetch", "kitchen")):
            arm.append((path.stem, request))
    return parking, arm, notes


def plan_runs(n: int, seed: int = 0, parking_share: float = PARKING_SHARE) -> tuple[list[StressRun], list[str]]:
    """``n`` runs drawn reproducibly from ``seed``: mostly parking, the rest Fetch with short limits."""
    parking, arm, notes = bundled_scenes()
    rng = np.random.default_rng(seed)
    runs = []
    for i in range(n):
        use_parking = not arm or (parking and rng.random() < parking_share)
        pool = parking if use_parking else arm
        name, request = pool[rng.integers(len(pool))]
        if use_parking:
            limit = PARKING_LIMIT
        else:
            limit = FETCH_LIMITS["place" if request.split()[0] in ("put", "place", "set", "move") else "pick"]
        runs.append(StressRun(i, name, request, int(rng.integers(2**31)), STRATEGIES[i % len(STRATEGIES)],
                              float(BIASES[rng.integers(len(BIASES))]), limit, ALGORITHMS[(i // len(STRATEGIES)) % 2]))
    return runs, notes


@functools.lru_cache(maxsize=16)  # keyed by scene name; more than the bundled scenes
def _scene_and_world(name: str):
    """Scenes and Drake worlds are built once per process."""
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    scene = load_scene(REPO / "yaml_scenes" / f"{name}.yaml")
    return scene, DrakeWorld(scene, visual=False)


def check_report(report, scene, world) -> list[str]:
    """Problems with a solved report's path, re-checked at a tenth of the edge resolution."""
    from lazyground.planning import path_is_valid

    res = report.result
    fine = report.settings.planner.resolution / 10
    if report.steps:  # pick and place: both steps, the lift and the carried object
        from lazyground.tasks.place import validate_pick_and_place

        return validate_pick_and_place(report, scene, fine) + _pick_and_place_trajectory_problems(report, scene, world, fine)
    problems = _trajectory_problems(report, world, world.start, fine)
    if not np.allclose(res.path[0], world.start):
        problems.append("path does not start at the start configuration")
    if not all(world.space.within_bounds(q) for q in res.path):
        problems.append("path leaves the joint limits")
    if not res.goal_region.reached(res.path[-1], world, tol=GOAL_TOLERANCE):
        problems.append(f"path ends outside goal region {res.goal_region.id}")
    bad = path_is_valid(planned_space(report, scene, world), world, res.path, fine)
    if bad >= 0:
        problems.append(f"segment {bad} collides at resolution {fine:g}")
    return problems


def planned_space(report, scene, world):
    """The space the report's path was planned in: a car's path is re-checked along its curves (what it drives),
    not along straight lines in (x, y, heading) between its samples, which the planner never checked."""
    from lazyground.tasks.car_space import planning_space

    return planning_space(scene, world.space, report.settings.planner.kinematics)


def _trajectory_problems(report, world, start, fine: float, from_first_free: bool = False) -> list[str]:
    """The timed trajectory of a solved report (issue #16), re-checked as a curve at ``fine``."""
    from lazyground.motion.validate import trajectory_problems

    motion = report.motion
    if motion is None or motion.trajectory is None:
        return ["solved without a trajectory" + (f" ({motion.note})" if motion is not None and motion.note else "")]
    return trajectory_problems(motion.trajectory, world.space, world, start, report.result.path[-1], fine, from_first_free)


def _pick_and_place_trajectory_problems(report, scene, world, fine: float) -> list[str]:
    """The pick's trajectory in the world; the place step's (lift first) with the object carried."""
    from lazyground.tasks.worlds import Worlds

    pick, place = report.steps
    carrying = Worlds(scene, world, visual=False).get(place.grasp)
    return (["pick: " + p for p in _trajectory_problems(pick, world, world.start, fine)]
            + ["place: " + p for p in _trajectory_problems(place, carrying, pick.result.path[-1], fine, from_first_free=True)])


def run_one(run: StressRun) -> dict:
    """Plan one run and check it; never raises (an exception is recorded as unexpected)."""
    from lazyground import api

    out = asdict(run) | {"status": "error", "time_s": None, "overshoot": None, "problems": [], "error": None}
    try:
        scene, world = _scene_and_world(run.scene)
        report = api.plan(scene, run.request, seed=run.seed, world=world, strategy=run.strategy,
                          goal_bias=run.goal_bias, time_limit=run.time_limit, algorithm=run.algorithm)
        res = report.result
        out.update(status=res.status.value, time_s=round(report.time_s, 4),
                   overshoot=round(report.time_s / run.time_limit - 1.0, 4), rejected=res.invalid_paths_rejected)
        if res.solved:
            out["problems"] = check_report(report, scene, world)
    except Exception as exc:  # the figure this tool exists for: must stay zero
        out["error"] = f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}"
    return out


def run_all(runs: list[StressRun], jobs: int = 1, progress=None) -> list[dict]:
    """Every run's record, in order; ``jobs`` > 1 uses worker processes."""
    rows = []
    if jobs <= 1:
        for r in runs:
            rows.append(run_one(r))
            if progress:
                progress(rows[-1])
        return rows
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        for row in pool.map(run_one, runs, chunksize=4):
            rows.append(row)
            if progress:
                progress(row)
    return rows


def summarize(rows: list[dict]) -> dict:
    """The figures: runs, statuses, invalid paths, unexpected exceptions, time-limit overshoot."""
    statuses: dict[str, int] = {}
    for r in rows:
        statuses[r["status"]] = statuses.get(r["status"], 0) + 1
    timed = [r for r in rows if r["overshoot"] is not None]
    timeouts = [r["overshoot"] for r in timed if r["status"] == "timeout"]
    per_scene = {}
    for r in rows:
        s = per_scene.setdefault(r["scene"], {"runs": 0, "solved": 0, "timeout": 0})
        s["runs"] += 1
        s["solved"] += r["status"] == "solved"
        s["timeout"] += r["status"] == "timeout"
    return {
        "runs": len(rows),
        "solved": statuses.get("solved", 0),
        "statuses": statuses,
        "invalid_paths": sum(bool(r["problems"]) for r in rows),
        "unexpected_exceptions": sum(r["error"] is not None for r in rows),
        "max_overshoot": max((r["overshoot"] for r in timed), default=0.0),
        "max_timeout_overshoot": max(timeouts, default=0.0),
        "timeouts": len(timeouts),
        "paths_rejected_by_revalidation": sum(r.get("rejected", 0) for r in rows),
        "per_scene": per_scene,
        "worst_overshoot": max(timed, key=lambda r: r["overshoot"], default=None),
        "examples": {
            "invalid": [r for r in rows if r["problems"]][:5],
            "errors": [r for r in rows if r["error"]][:5],
        },
    }


def figures_lines(summary: dict, wall_s: float | None = None) -> list[str]:
    s = summary
    lines = [
        f"runs: {s['runs']}  solved: {s['solved']}  statuses: {s['statuses']}",
        f"invalid paths found: {s['invalid_paths']}",
        f"unexpected exceptions: {s['unexpected_exceptions']}",
        f"max time-limit overshoot: {s['max_overshoot']:+.2%} over all runs; {s['max_timeout_overshoot']:+.2%} over {s['timeouts']} timeouts",
        f"paths rejected (and re-planned) by the planner's own re-validation: {s['paths_rejected_by_revalidation']}",
    ]
    w = s["worst_overshoot"]
    if w is not None:
        lines.append(f"  worst overshoot: run {w['index']} {w['scene']} ({w['request']!r}, seed {w['seed']}, {w['algorithm']}, {w['strategy']}, "
                     f"bias {w['goal_bias']:g}): {w['status']} after {w['time_s']:.3f} s of {w['time_limit']:g} s")
    for name, st in sorted(s["per_scene"].items()):
        lines.append(f"  {name}: {st['runs']} runs, {st['solved']} solved, {st['timeout']} timeouts")
    for r in s["examples"]["invalid"] + s["examples"]["errors"]:
        lines.append(f"  ! run {r['index']} {r['scene']} seed {r['seed']}: {r['problems'] or r['error']}")
    if wall_s is not None:
        lines.append(f"wall time: {wall_s:.0f} s")
    return lines


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=DEFAULT_RUNS, help="number of plans (default: $LAZYGROUND_STRESS_RUNS or 40)")
    p.add_argument("--jobs", type=int, default=1, help="worker processes (default 1)")
    p.add_argument("--seed", type=int, default=0, help="draws the list of runs")
    p.add_argument("--out", help="write every run and the figures to this JSON file")
    args = p.parse_args(argv)
    runs, notes = plan_runs(args.runs, args.seed)
    for note in notes:
        print(f"note: {note}", file=sys.stderr)
    t0 = time.perf_counter()
    done = [0]

    def progress(row):
        done[0] += 1
        if done[0] % 50 == 0 or row["problems"] or row["error"]:
            print(f"[{done[0]}/{len(runs)}] {row['scene']} {row['status']} {row['problems'] or row['error'] or ''}", file=sys.stderr, flush=True)

    rows = run_all(runs, args.jobs, progress)
    summary = summarize(rows)
    wall = time.perf_counter() - t0
    print("\n".join(figures_lines(summary, wall)))
    if args.out:
        Path(args.out).write_text(json.dumps({"summary": summary, "wall_s": wall, "notes": notes, "rows": rows}, indent=1))
    return 1 if summary["invalid_paths"] or summary["unexpected_exceptions"] else 0


if __name__ == "__main__":
    sys.exit(main())
