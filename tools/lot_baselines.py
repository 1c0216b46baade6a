"""What the baselines of issue #33 cost on the fixed-layout lots, piece by piece (a diagnosis, not the benchmark).

For each N, on ``lot:N:2:0:576`` (the bench's ``lot-fixed`` sweep):

* ``nearest-first``: the rank of the first reachable spot in the baseline's order (distance from the car's
  start), so its time is at least (rank - 1) x the per-call budget: every nearer spot is blocked, its parked
  pose valid, so its call runs out its budget; and the time a call for the reachable spot alone takes
  (``--alone-seeds``), which is the least a per-call budget must allow;
* ``eager``: the up-front phase (a goal state for every spot, before the one planner call), timed alone, and
  (``--search-seeds``) the whole baseline against the same up-front phase followed by our strategy's search
  (``--strategy``): if the two differ by the search alone, eager's cost over ours is the strategy's, not the
  eagerness.

Times are wall-clock seconds of this process (say the machine's load with them). Example (quiet, ~6 min)::

    PYTHONPATH=. python3 tools/lot_baselines.py --sizes 64,256,512 --upfront-seeds 5 --alone-seeds 10 --search-seeds 5
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace

import numpy as np

import grounding
from lazyground.api import planner_settings
from lazyground.bench import baselines
from lazyground.bench.families import generate, load_family_scene, parse_key
from lazyground.bench.sweep import FIXED_SLOTS
from lazyground.drake.world import DrakeWorld
from lazyground.goals import goal_source_for
from lazyground.planning.rrt import solve
from lazyground.planning.stop import StopCondition
from lazyground.settings import Algorithm, Strategy
from lazyground.tasks.car_space import planning_space


def _q(xs) -> str:
    """median [min-max] of seconds."""
    return f"{np.median(xs):.2f} [{min(xs):.2f}-{max(xs):.2f}]" if xs else "-"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", default="64,256,512")
    p.add_argument("--upfront-seeds", type=int, default=5, help="seeds of eager's up-front phase alone")
    p.add_argument("--alone-seeds", type=int, default=0, help="seeds of a planner call for the reachable spot alone")
    p.add_argument("--search-seeds", type=int, default=0, help="seeds of eager (consecutive) and eager + --strategy")
    p.add_argument("--strategy", default=Strategy.COVER_CONNECT.value)
    p.add_argument("--time-limit", type=float, default=60.0, help="seconds per planner call")
    a = p.parse_args(argv)
    print("| N | reachable spot's rank nearest-first | nearest-first >= (rank - 1) x 10 s | eager up-front s (goal states) | "
          "reachable spot alone s (solved; within 2 / 5 / 10 s) | eager s (solved) | eager up-front + "
          f"{a.strategy} s (solved) |\n|---|---|---|---|---|---|---|")
    for n in [int(x) for x in a.sizes.split(",")]:
        key = f"lot:{n}:2:0:{FIXED_SLOTS}"
        scene = load_family_scene(key)
        world = DrakeWorld(scene, visual=False)
        reach = set(generate(parse_key(key))["expect"][0]["reachable"])
        regions = grounding.ground("park", scene).goal_regions
        settings = planner_settings(scene, strategy=Strategy.CONSECUTIVE.value, algorithm=Algorithm.BIDIRECTIONAL,
                                    time_limit=a.time_limit)
        space = planning_space(scene, world.space, settings.kinematics)
        groups = baselines.nearest_first_order(scene, world, regions)
        rank = next(i + 1 for i, g in enumerate(groups) if g[0].object in reach)
        upfront, states = [], []
        for seed in range(a.upfront_seeds):
            src = baselines.EagerSource(regions, world)
            t0 = time.perf_counter()
            states.append(len(src.draw(len(regions), np.random.default_rng(seed), StopCondition.after(None))))
            upfront.append(time.perf_counter() - t0)
        alone, alone_ok, within = [], 0, {2.0: 0, 5.0: 0, 10.0: 0}  # budgets a nearest-first call could have
        for seed in range(a.alone_seeds):
            r = solve(space, world, goal_source_for(groups[rank - 1], world), world.start, settings,
                      np.random.default_rng(seed), seed=seed)
            alone.append(r.time_s)
            alone_ok += r.solved
            for b in within:
                within[b] += r.solved and r.time_s <= b
        runs = {Strategy.CONSECUTIVE.value: ([], 0), a.strategy: ([], 0)}
        for strategy in runs if a.search_seeds else ():
            times, ok = runs[strategy]
            for seed in range(a.search_seeds):
                r = solve(space, world, baselines.EagerSource(regions, world), world.start,
                          replace(settings, strategy=Strategy(strategy)), np.random.default_rng(seed), seed=seed)
                times.append(r.time_s)
                ok += r.solved
            runs[strategy] = (times, ok)
        (e, e_ok), (s, s_ok) = runs[Strategy.CONSECUTIVE.value], runs[a.strategy]
        print(f"| {n} | {rank} of {len(groups)} | {(rank - 1) * baselines.CALL_BUDGET:g} s | {_q(upfront)} ({np.median(states or [0]):.0f}) | "
              f"{_q(alone)} ({alone_ok}/{a.alone_seeds}; {' / '.join(str(v) for v in within.values())}) | {_q(e)} ({e_ok}/{a.search_seeds}) | {_q(s)} ({s_ok}/{a.search_seeds}) |",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
