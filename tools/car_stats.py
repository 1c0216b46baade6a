"""Per-seed figures of the car planner (issue #17): iterations, planning time, gear changes, driven length.

    PYTHONPATH=. python3 tools/car_stats.py parking_2 --seeds 0-39 --strategy consecutive

Prints one JSON line per seed and a summary: iterations (load-independent), the planner's
process time (CPU seconds of the search alone, less sensitive to load than wall time),
and the gear changes and driven length of the planner's path and of the path after the car
shortcut (lazyground.motion.car_shortcut). No time limit: runs stop at --max-iterations.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from lazyground import api
from lazyground.drake.world import DrakeWorld
from lazyground.planning import rrt
from lazyground.tasks.car_space import planning_space
from lazyground.scene import load_scene
from lazyground.settings import Kinematics, Strategy


def _seeds(text: str) -> range:
    lo, _, hi = text.partition("-")
    return range(int(lo), int(hi or lo) + 1)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("--seeds", default="0-19", help="first-last, inclusive")
    ap.add_argument("--strategy", default=Strategy.REWARD_PENALTY.value)
    ap.add_argument("--kinematics", default=Kinematics.REEDS_SHEPP.value)
    ap.add_argument("--max-iterations", type=int, default=40_000)
    args = ap.parse_args()
    scene = load_scene(args.scene)
    world = DrakeWorld(scene, visual=False)
    space = planning_space(scene, world.space, args.kinematics)
    cpu: list[float] = []
    solve = rrt.solve

    def timed(*a, **k):  # the search alone: grounding, shortcut and timing excluded
        c0 = time.process_time()
        out = solve(*a, **k)
        cpu.append(time.process_time() - c0)
        return out

    import lazyground.tasks.reach as reach
    reach.solve = timed
    rows = []
    for seed in _seeds(args.seeds):
        report = api.plan(scene, "park", seed=seed, world=world, strategy=args.strategy, kinematics=args.kinematics,
                          time_limit=1e6, max_iterations=args.max_iterations)
        r, motion = report.result, report.motion
        row = dict(seed=seed, status=r.status.value, iterations=r.iterations, search_cpu_s=round(cpu[-1], 3),
                   region=r.goal_region.id if r.goal_region else "")
        if r.solved and report.cusps is not None:
            raw = motion.raw_path if motion is not None else r.path
            row.update(raw_cusps=space.cusps(raw), cusps=report.cusps, raw_length=round(motion.raw_length if motion else r.path_length, 2),
                       length=round(r.path_length, 2), shortcut_s=round(motion.shortcut_s, 3) if motion else 0.0)
        rows.append(row)
        print(json.dumps(row), flush=True)
    its = np.array([row["iterations"] for row in rows])
    solved = [row for row in rows if row["status"] == "solved"]
    print(f"{args.scene} {args.strategy} {args.kinematics}: solved {len(solved)}/{len(rows)}; iterations median "
          f"{np.median(its):.0f} mean {its.mean():.0f} max {its.max()}; search CPU s median {np.median(cpu):.2f} "
          f"mean {np.mean(cpu):.2f} max {np.max(cpu):.2f}")
    if solved and "cusps" in solved[0]:
        pick = lambda key: np.array([row[key] for row in solved])  # noqa: E731
        print(f"gear changes median {np.median(pick('raw_cusps')):.0f} -> {np.median(pick('cusps')):.0f} (mean "
              f"{pick('raw_cusps').mean():.1f} -> {pick('cusps').mean():.1f}); driven m median "
              f"{np.median(pick('raw_length')):.1f} -> {np.median(pick('length')):.1f}; shortcut s median "
              f"{np.median(pick('shortcut_s')):.2f}")


if __name__ == "__main__":
    main()
