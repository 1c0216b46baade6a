"""Why planning time grows with N on the fixed-layout lots (issue #33): a diagnosis, not a benchmark.

For each N and seed it runs the two-tree planner (iteration-capped) on ``lot:N:2:0:576`` and reports the
iterations, the milliseconds per iteration, where the goal forest's uncredited extensions went (trees of
reachable spots or of blocked ones) and how often the strategy selected a reachable spot's sample. With
``--oracle`` it also runs two oracles that know which spots are reachable (they bound what any rule that
tells reachable from blocked spots could gain):

* ``forest``: the blocked spots' goal trees are left out of the whole forest's nearest-neighbour queries
  (they still grow when the strategy selects them);
* ``select``: the strategy's choice is a reachable spot's sample whenever one has been drawn.

The oracles patch the planner's internals in this process only (a diagnosis; nothing in the library reads
them). Example (about 6 min on a quiet machine)::

    PYTHONPATH=. python3 tools/lot_growth.py --sizes 8,64,256 --seeds 0-9 --cap 2000 --oracle

The honest baseline for the cost of ambiguity: the same planner with only the reachable spots' goal regions
(``--goals reachable``; the lot's geometry still changes with N: blocked spots' barriers narrow the aisles and
flank the reachable spots at N = 512)::

    PYTHONPATH=. python3 tools/lot_growth.py --sizes 8,64,256,512 --seeds 0-9 --cap 2000 --goals reachable

With the reach prior (the default) the blocked spots are never sampled; ``--no-reach-prior`` samples them as before.

The paper's one-tree planner on the same lots (no goal forest; 4,000-iteration cap)::

    PYTHONPATH=. python3 tools/lot_growth.py --sizes 8,64 --seeds 0-5 --cap 4000 \\
        --algorithm rrt --strategy reward-penalty --goal-bias 0.05
"""

from __future__ import annotations

import argparse
import collections
import sys

import numpy as np

import grounding
from lazyground import api
from lazyground.bench.families import generate, load_family_scene, parse_key
from lazyground.bench.sweep import FIXED_SLOTS
from lazyground.drake.world import DrakeWorld
from lazyground.goals import goal_source_for
from lazyground.planning import birrt, search
from lazyground.planning.nn import NearestNeighbors
from lazyground.planning.rrt import solve
from lazyground.planning.tree import Tree
from lazyground.settings import Algorithm, Strategy
from lazyground.tasks.car_space import planning_space

MODES = ("none", "forest", "select", "forest+select")
STATE: dict = {"mode": "none", "reach": set(), "search": None, "counts": collections.Counter()}


def _reachable(s, label: int) -> bool:
    return s.goals.regions[s.samples[label].region].id.split("/")[0] in STATE["reach"]


def _patch() -> None:
    grow, extend, add, select = birrt.grow_bidirectional, birrt._extend, Tree._add, search.Search.select

    def grow_(s, start):
        STATE["search"] = s
        return grow(s, start)

    def extend_(s, tree, q, step, label=None):
        near, b = extend(s, tree, q, step, label)
        if tree is not s.trees[0] and near >= 0:
            STATE["counts"]["goal steps", "reachable" if _reachable(s, tree.labels[near]) else "blocked", b >= 0] += 1
        elif tree is s.trees[0]:
            STATE["counts"]["start steps", b >= 0] += 1
        return near, b

    def add_(self, q, parent, label, goal_biased, checked):
        s = STATE["search"]
        if not (self._per_label and "forest" in STATE["mode"] and label >= 0 and not _reachable(s, label)):
            return add(self, q, parent, label, goal_biased, checked)
        i = add(self, q, parent, label, goal_biased, checked)  # then moved out of the whole forest's index
        self.nn.remove([i])
        return i

    def select_(self):
        gi = None
        if "select" in STATE["mode"]:
            good = [i for i, g in enumerate(self.samples) if i not in self.dead and _reachable(self, i)]
            if good:
                gi = good[int(self.rng.integers(len(good)))]
                self.samples[gi].attempts += 1
        gi = select(self) if gi is None else gi
        if gi is not None:
            STATE["counts"]["selections", "reachable" if _reachable(self, gi) else "blocked"] += 1
        return gi

    birrt._extend, Tree._add, search.Search.select = extend_, add_, select_
    from lazyground.planning import rrt

    for key, fn in rrt.ALGORITHMS.items():
        if fn is grow:
            rrt.ALGORITHMS[key] = grow_


def _plan_reachable(scene, world, seed: int, a, bias: dict):
    """The planner's result on the reachable spots' goal regions only (grounded as ``park``, then filtered)."""
    regions = tuple(r for r in grounding.ground("park", scene).goal_regions if r.object in STATE["reach"])
    settings = api.planner_settings(scene, strategy=a.strategy, algorithm=a.algorithm, time_limit=a.time_limit,
                                    max_iterations=a.cap, **bias)
    space = planning_space(scene, world.space, settings.kinematics)
    return solve(space, world, goal_source_for(regions, world), world.start, settings, np.random.default_rng(seed),
                 seed=seed)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", default="8,64,256")
    p.add_argument("--seeds", default="0-4", help="a-b or a comma list")
    p.add_argument("--cap", type=int, default=2000, help="iteration cap")
    p.add_argument("--time-limit", type=float, default=60.0)
    p.add_argument("--strategy", default=Strategy.COVER_CONNECT.value)
    p.add_argument("--algorithm", default=Algorithm.BIDIRECTIONAL.value,
                   help=f"{Algorithm.RRT}: the one-tree planner (no goal forest: the forest columns stay empty, "
                   "the oracles change only its strategy's choice)")
    p.add_argument("--goal-bias", type=float, default=None, help="default: the scene's (0.05)")
    p.add_argument("--oracle", action="store_true", help="also run the oracles")
    p.add_argument("--goals", choices=("all", "reachable"), default="all",
                   help="reachable: plan to the reachable spots' goal regions only (no ambiguity)")
    p.add_argument("--no-reach-prior", action="store_true",
                   help="sample every spot's regions, also those the reach prior proves unreachable (#33)")
    a = p.parse_args(argv)
    seeds = (list(range(int(a.seeds.split("-")[0]), int(a.seeds.split("-")[1]) + 1)) if "-" in a.seeds
             else [int(x) for x in a.seeds.split(",")])
    _patch()
    print("| N | mode | solved | median iterations | median s | ms / iteration | goal steps in reachable trees | "
          "selections of reachable samples |\n|---|---|---|---|---|---|---|---|")
    for n in [int(x) for x in a.sizes.split(",")]:
        key = f"lot:{n}:2:0:{FIXED_SLOTS}"
        scene = load_family_scene(key)
        world = DrakeWorld(scene, visual=False)
        STATE["reach"] = set(generate(parse_key(key))["expect"][0]["reachable"])
        for mode in MODES if a.oracle else MODES[:1]:
            STATE["mode"] = mode
            STATE["counts"] = collections.Counter()
            its, secs, solved = [], [], 0
            for seed in seeds:
                bias = {} if a.goal_bias is None else {"goal_bias": a.goal_bias}
                if a.goals == "all":
                    r = api.plan(scene, "park", seed=seed, world=world, strategy=a.strategy, algorithm=a.algorithm,
                                 time_limit=a.time_limit, max_iterations=a.cap, reach_prior=not a.no_reach_prior,
                                 **bias).result
                else:
                    r = _plan_reachable(scene, world, seed, a, bias)
                secs.append(r.time_s)  # the planner's own time (no grounding, shortcut or timing)
                its.append(r.iterations)
                solved += r.status.value == "solved"
            c = STATE["counts"]
            goal_r = sum(v for k, v in c.items() if k[:2] == ("goal steps", "reachable"))
            goal_all = sum(v for k, v in c.items() if k[0] == "goal steps")
            sel_r, sel_all = c["selections", "reachable"], c["selections", "reachable"] + c["selections", "blocked"]
            print(f"| {n} | {mode} | {solved}/{len(seeds)} | {np.median(its):.0f} | {np.median(secs):.2f} | "
                  f"{1000 * sum(secs) / max(1, sum(its)):.1f} | {goal_r} of {goal_all} | {sel_r} of {sel_all} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
