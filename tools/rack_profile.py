"""Issue #33, arm racks: where cover's time and iterations go, per can kind (reachable / window / caged / behind).

Instruments one process (CPU clock): the IK attempts and goal samples per kind, the goal-tree steps (edge checks)
per kind and the start tree's, their CPU seconds, the goal turns the strategy spent on each kind's samples, and
each kind's goal trees' size. Usage (repository root):
  PYTHONPATH=. python3 tools/rack_profile.py ROBOT N LAYOUTS [--strategy cover] [--seed 0]
"""
from __future__ import annotations

import argparse
import collections
import sys
import time

import numpy as np

import lazyground.planning.birrt as birrt
import lazyground.planning.rrt as rrt_module
import lazyground.planning.stop as stop_module
from lazyground import api
from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.bench.runner import load_problem
from lazyground.planning.search import Search
from lazyground.settings import Algorithm, Strategy

STATE: dict = {}


def _kind_of_label(s, label: int) -> str:
    return STATE["kinds"][s.goals.regions[s.samples[label].region].object]


def patch() -> None:
    step0, select0, grow0 = birrt._step, Search.select, birrt.grow_bidirectional

    def step(s, tree, parent, q_new):
        t0 = time.process_time()
        new = step0(s, tree, parent, q_new)
        k = "start" if tree is s.trees[0] else _kind_of_label(s, tree.labels[parent])
        c = STATE["c"]
        c[f"steps:{k}"] += 1
        c[f"free:{k}"] += new >= 0
        c[f"step_s:{k}"] += time.process_time() - t0
        return new

    def select(s):
        gi = select0(s)
        if gi is not None:
            STATE["c"][f"select:{_kind_of_label(s, gi)}"] += 1
        return gi

    def grow(s, start):
        STATE["search"] = s
        return grow0(s, start)

    birrt._step, Search.select = step, select
    rrt_module.ALGORITHMS[Algorithm.BIDIRECTIONAL] = grow


KINDS = ("reachable", "window", "caged", "behind")


def run(robot: str, n: int, layout: int, strategy: str, seed: int) -> dict:
    key = f"rack:{robot}:{n}:1:{layout}"
    STATE["kinds"] = can_kinds(generate(parse_key(key)))
    problem = load_problem(key)
    STATE["c"] = collections.Counter()
    t0 = time.process_time()
    rep = api.plan(problem.scene, problem.request, seed=seed, world=problem.world, strategy=strategy,
                   algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=60.0)
    cpu = time.process_time() - t0
    r, c, s = rep.result, STATE["c"], STATE["search"]
    row = dict(key=key, solved=r.solved, cpu=cpu, plan_s=r.time_s, ik_s=r.goal_sampling_s, iterations=r.iterations,
               ground_s=rep.grounding_s)
    kind_of_region = [STATE["kinds"][reg.object] for reg in r.regions]
    tg = s.trees[1]
    sizes = collections.Counter(tg.labels)
    for k in KINDS:
        regs = [j for j, kk in enumerate(kind_of_region) if kk == k]
        samples = [i for i, g in enumerate(r.goal_samples) if kind_of_region[g.region] == k]
        row[k] = dict(regions=len(regs), attempts=sum(r.region_stats[j].attempts for j in regs),
                      valid=sum(r.region_stats[j].valid for j in regs), samples=len(samples),
                      nodes=sum(sizes[i] for i in samples), select=c[f"select:{k}"], steps=c[f"steps:{k}"],
                      free=c[f"free:{k}"], step_s=round(c[f"step_s:{k}"], 3))
    row["start"] = dict(nodes=len(s.trees[0]), steps=c["steps:start"], free=c["free:start"], step_s=round(c["step_s:start"], 3))
    return row


def main(argv):
    p = argparse.ArgumentParser()
    p.add_argument("robot"); p.add_argument("n", type=int); p.add_argument("layouts")
    p.add_argument("--strategy", default=Strategy.COVER.value); p.add_argument("--seed", type=int, default=0)
    a = p.parse_args(argv)
    stop_module.CLOCK = time.process_time
    patch()
    lays = range(int(a.layouts.split("-")[0]), int(a.layouts.split("-")[1]) + 1) if "-" in a.layouts else [int(x) for x in a.layouts.split(",")]
    run(a.robot, a.n, lays[0], a.strategy, a.seed)  # warm-up
    rows = [run(a.robot, a.n, lay, a.strategy, a.seed) for lay in lays]
    import json
    for row in rows:
        print(json.dumps(row), flush=True)
    med = lambda xs: float(np.median(xs))
    print(f"# {a.robot} N={a.n} {len(rows)} layouts, medians: cpu {med([r['cpu'] for r in rows]):.3f} plan {med([r['plan_s'] for r in rows]):.3f} "
          f"ik {med([r['ik_s'] for r in rows]):.3f} iterations {med([r['iterations'] for r in rows]):.0f} solved {sum(r['solved'] for r in rows)}")
    print("# sums over layouts: kind regions attempts valid samples goal-tree-nodes selects steps free step_s")
    for k in KINDS:
        tot = {f: sum(r[k][f] for r in rows) for f in rows[0][k]}
        print(f"# {k:9s} " + " ".join(f"{f}={tot[f]:.3f}" if f == "step_s" else f"{f}={tot[f]}" for f in tot))
    tot = {f: sum(r["start"][f] for r in rows) for f in rows[0]["start"]}
    print("# start     " + " ".join(f"{f}={v:.3f}" if f == "step_s" else f"{f}={v}" for f, v in tot.items()))
    print(f"# total cpu {sum(r['cpu'] for r in rows):.2f} plan {sum(r['plan_s'] for r in rows):.2f} ik {sum(r['ik_s'] for r in rows):.2f} "
          f"iterations {sum(r['iterations'] for r in rows)}")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
