"""Plan "pick up the can" for a can inside an open box, over variants and seeds (issue 34); print a table.

    PYTHONPATH=$PWD python3 tools/open_box_report.py --seeds 3   # every variant (3 robots x 2 distances x 3 heights x 4 places)
    PYTHONPATH=$PWD python3 tools/open_box_report.py --seeds 3 --robot fetch --size 0.3 --distance far
    PYTHONPATH=$PWD python3 tools/open_box_report.py --seeds 3 --runs         # also one line per run (seed, status, region)
    PYTHONPATH=$PWD python3 tools/open_box_report.py --rates 200 --robot fetch --goal-learning 0   # valid goals per attempt

With ``--rates N``, no planning: per variant and seed, the goal sampler makes N attempts on every grasp
region (never giving one up) and the table gives valid goals per attempt, region by region.

Runs are capped by ``--max-iterations`` (default 20,000) and the robot's time limit; each row says
solved/total, the seeds that failed, the median time of the solved runs and the grasps tried over all runs.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import numpy as np
import yaml


def main(argv=None) -> int:
    from lazyground import api
    from lazyground.bench.open_box import PLACES, ROBOTS, scene_dict, variants
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import parse_scene

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=3, help="seeds 0..N-1 per variant")
    parser.add_argument("--robot", action="append", choices=sorted(ROBOTS), help="robots (repeatable; default: all)")
    parser.add_argument("--size", action="append", type=float, help="inner box sizes, m (repeatable; default 0.2)")
    parser.add_argument("--height", action="append", type=float, help="wall heights, m (repeatable; default 0.06, 0.09, 0.12)")
    parser.add_argument("--place", action="append", choices=sorted(PLACES), help="where the can stands (repeatable)")
    parser.add_argument("--distance", action="append", choices=["near", "far"], help="the box near or far (repeatable)")
    parser.add_argument("--max-iterations", type=int, default=20000)
    parser.add_argument("--runs", action="store_true", help="one line per run too")
    parser.add_argument("--rates", type=int, default=0, help="N: valid goals per attempt over N attempts per region")
    parser.add_argument("--goal-learning", type=float, default=None, help="the goal_learning setting (default: its default)")
    args = parser.parse_args(argv)
    overrides = {} if args.goal_learning is None else {"goal_learning": args.goal_learning}
    chosen = variants(**{k: tuple(v) for k, v in (("robots", args.robot), ("sizes", args.size), ("heights", args.height),
                                                   ("places", args.place),
                                                   ("distances", args.distance)) if v})
    if args.rates:
        return rates(chosen, args.seeds, args.rates, overrides)
    print("| variant | solved | failed seeds | median s | grasps tried | reached |")
    print("| --- | --- | --- | --- | --- | --- |")
    total = solved = 0
    for v in chosen:
        scene = parse_scene(yaml.safe_dump(scene_dict(v), sort_keys=False), f"{v.name}.yaml")
        world = DrakeWorld(scene, visual=False)
        times, failed, tried, reached = [], [], 0, set()
        for seed in range(args.seeds):
            t0 = time.perf_counter()
            report = api.plan(scene, "pick up the can", seed=seed, world=world, max_iterations=args.max_iterations, **overrides)
            dt = time.perf_counter() - t0
            res = report.result
            attempts = sum(st.attempts for st in res.region_stats) if getattr(res, "region_stats", None) else 0
            tried += attempts
            if res.status.value == "solved":
                times.append(report.time_s)
                reached.add(res.goal_region.label if getattr(res, "goal_region", None) else "?")
            else:
                failed.append(str(seed))
            if args.runs:
                print(f"  {v.name} seed {seed}: {res.status.value} {dt:.2f} s, {attempts} attempts; {res.message or ''}",
                      file=sys.stderr, flush=True)
        total += args.seeds
        solved += len(times)
        med = f"{statistics.median(times):.2f}" if times else "-"
        print(f"| {v.name} | {len(times)}/{args.seeds} | {','.join(failed) or '-'} | {med} | {tried} | {', '.join(sorted(reached))} |",
              flush=True)
    print(f"| **all** | {solved}/{total} | | | | |")
    return 0


def rates(chosen, seeds: int, attempts: int, overrides: dict) -> int:
    """Valid goal samples per attempt, per variant and grasp region, summed over seeds."""
    import grounding
    from lazyground.bench.open_box import scene_dict
    from lazyground.drake.ik import IKGoalSource
    from lazyground.drake.world import DrakeWorld
    from lazyground.planning.stop import never
    from lazyground.scene import parse_scene
    from lazyground.settings import GoalSamplingSettings

    print("| variant | region | valid / attempts |")
    print("| --- | --- | --- |")
    for v in chosen:
        scene = parse_scene(yaml.safe_dump(scene_dict(v), sort_keys=False), f"{v.name}.yaml")
        world = DrakeWorld(scene, visual=False)
        regions = grounding.ground("pick up the can", scene).goal_regions
        valid, tried = {}, {}
        for seed in range(seeds):
            source = IKGoalSource(regions, world, give_up_after=10**9, sampling=GoalSamplingSettings(**overrides))
            rng = np.random.default_rng(seed)
            while min(st.attempts for st in source.stats) < attempts:
                source.draw(8, rng, never())
            for r, st in zip(regions, source.stats):
                valid[r.label] = valid.get(r.label, 0) + st.valid
                tried[r.label] = tried.get(r.label, 0) + st.attempts
        for label in valid:
            print(f"| {v.name} | {label} | {valid[label]}/{tried[label]} ({100 * valid[label] / tried[label]:.1f}%) |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
