"""Issue #33, arm racks: the figures of the N = 64 / 256 targets on CPU seconds (robust to a busy machine), one run per
rack layout: our strategies (api.plan, bidirectional), ground-then-plan nearest-first and, optionally, eager all-goal IK.

Every run's clock is this process's CPU time (``lazyground.planning.stop.CLOCK = time.process_time``): deadlines and
reported times, the baselines' budgets included, count only the CPU this process got, so a shared machine's load does
not stretch them (on a quiet machine CPU and wall time agree within a few per cent: the planner is single-threaded).

Nearest-first is measured call by call, without its total limit: each can nearer than the reachable one is sampled by
its own goal source (IK) until it yields a valid goal sample or is given up; a can that yields one costs the whole call
budget (its can is unreachable by construction, tests/drake/test_families_reach.py, so the planner call runs to its
budget), one that is given up costs its IK seconds; the reachable can's call is a real planner call with the budget.
``--real-nf`` runs the real baseline (lazyground.bench.baselines) instead, with a TOTAL limit, to check the sum.

Usage (from the repository root):
  PYTHONPATH=. python3 tools/rack_targets.py ROBOT N LAYOUTS [--strategies cover,consecutive] [--limit 30]
      [--budget 10] [--eager] [--eager-limit 120] [--real-nf TOTAL] [--seed 0] [--jsonl OUT.jsonl] [--no-reach-prior]
LAYOUTS: 0-19 or 0,3,5. Prints one JSON line per layout and a summary (medians, ratios, Mann-Whitney p);
  PYTHONPATH=. python3 tools/rack_targets.py summary A.jsonl B.jsonl   summarises rows written with --jsonl.
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

import lazyground.planning.stop as stop_module
from lazyground import api
from lazyground.api import planner_settings
from lazyground.bench.baselines import CALL_BUDGET, nearest_first_order, run_baseline
from lazyground.bench.compare import mann_whitney_p
from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import REACHABLE, can_kinds
from lazyground.bench.runner import load_problem
from lazyground.goals import goal_source_for
from lazyground.planning.rrt import solve
from lazyground.planning.stop import StopCondition
from lazyground.settings import Algorithm, Strategy


def _layouts(text: str) -> list[int]:
    if "-" in text:
        a, b = text.split("-")
        return list(range(int(a), int(b) + 1))
    return [int(x) for x in text.split(",")]


def nearest_first(problem, regions, kinds, budget: float, seed: int) -> dict:
    """Nearest-first's cost, call by call (see the module docstring)."""
    world, scene = problem.world, problem.scene
    settings = planner_settings(scene, strategy=Strategy.CONSECUTIVE, algorithm=Algorithm.BIDIRECTIONAL, time_limit=budget)
    rng = np.random.default_rng(seed)
    calls, total = [], 0.0
    for group in nearest_first_order(scene, world, regions):
        kind = kinds[group[0].object]
        t0 = stop_module.CLOCK()
        if kind != REACHABLE:
            src, got = goal_source_for(group, world), False
            stop = StopCondition.after(budget)
            while not got and not src.exhausted() and not stop.should_stop():
                got = bool(src.draw(1, rng, stop))
            cost = budget if got else min(budget, stop_module.CLOCK() - t0)
            calls.append((kind, "budget" if got else "given up", round(cost, 3), src.total_attempts))
            total += cost
            continue
        source = goal_source_for(group, world)
        r = solve(world.space, world, source, world.start, settings, rng, seed=seed, setup_s=stop_module.CLOCK() - t0)
        total += r.time_s
        calls.append((kind, r.status.value, round(r.time_s, 3), sum(st.attempts for st in r.region_stats)))
        if r.solved:
            return dict(status="solved", time=round(total, 3), calls=calls)
    return dict(status="unsolved (the reachable can's call failed; the cans after it not added)", time=round(total, 3), calls=calls)


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("robot")
    p.add_argument("n", type=int)
    p.add_argument("layouts", type=_layouts)
    p.add_argument("--strategies", default=f"{Strategy.COVER.value},{Strategy.CONSECUTIVE.value}")
    p.add_argument("--limit", type=float, default=30.0, help="our runs' limit, CPU s (unsolved counted at it)")
    p.add_argument("--budget", type=float, default=CALL_BUDGET, help="nearest-first: CPU s per planner call")
    p.add_argument("--eager", action="store_true", help="also run eager all-goal IK (real baseline)")
    p.add_argument("--eager-limit", type=float, default=120.0)
    p.add_argument("--real-nf", type=float, default=0.0, metavar="TOTAL", help="run the real nearest-first with this total limit")
    p.add_argument("--seed", type=int, default=0, help="planner seed (the same for every layout)")
    p.add_argument("--no-nf", action="store_true", help="skip nearest-first")
    p.add_argument("--jsonl", help="also append the rows to this file")
    p.add_argument("--no-reach-prior", action="store_true", help="sample every region (setting reach_prior: false)")
    p.add_argument("--no-warm-up", action="store_true", help="skip the untimed first plan (compiles kernels and caches "
                   "once per process: 0.5 CPU s, charged to whichever strategy ran first on the first layout)")
    if argv[:1] == ["summary"]:  # summary FILE.jsonl ...: the rows of earlier runs (e.g. layouts split over processes)
        rows = [json.loads(line) for f in argv[1:] for line in open(f) if line.strip()]
        names = {m.value for m in Strategy}
        summary(rows, list(dict.fromkeys(k for r in rows for k in r if k in names)))  # as run: ours first
        return 0
    a = p.parse_args(argv)
    stop_module.CLOCK = time.process_time
    strategies = [s for s in a.strategies.split(",") if s]
    rows = []
    if not a.no_warm_up and strategies:
        problem = load_problem(f"rack:{a.robot}:{a.n}:1:{a.layouts[0]}")
        api.plan(problem.scene, problem.request, seed=a.seed, world=problem.world, strategy=strategies[0],
                 algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=a.limit, reach_prior=not a.no_reach_prior)
    for lay in a.layouts:
        key = f"rack:{a.robot}:{a.n}:1:{lay}"
        kinds = can_kinds(generate(parse_key(key)))
        problem = load_problem(key)
        regions, _ = problem.ground()
        row = dict(key=key, seed=a.seed, clock="cpu")
        for strat in strategies:
            rep = api.plan(problem.scene, problem.request, seed=a.seed, world=problem.world, strategy=strat,
                           algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=a.limit, reach_prior=not a.no_reach_prior)
            r = rep.result
            row[strat] = dict(solved=r.solved, time=round(rep.grounding_s + r.time_s if r.solved else a.limit, 3),
                              iterations=r.iterations, attempts=sum(st.attempts for st in r.region_stats),
                              ik_s=round(r.goal_sampling_s, 3), dropped=sum(bool(st.unreachable) for st in r.region_stats),
                              total=round(rep.total_s, 3), setup=round(rep.setup_s, 3))  # as the user waits; set-up (the prior)
        prior = None if a.no_reach_prior else problem.world.reach_prior()  # built by the first plan, as set-up
        row["prior_s"] = round(getattr(prior, "build_s", 0.0), 3)
        if not a.no_nf:
            row["nearest-first"] = nearest_first(problem, regions, kinds, a.budget, a.seed)
        settings = planner_settings(problem.scene, strategy=Strategy.CONSECUTIVE, algorithm=Algorithm.BIDIRECTIONAL,
                                    time_limit=a.eager_limit)
        if a.real_nf:
            res, secs, _, att = run_baseline("nearest-first", problem.scene, problem.world, regions, problem.world.space,
                                             planner_settings(problem.scene, strategy=Strategy.CONSECUTIVE,
                                                              algorithm=Algorithm.BIDIRECTIONAL, time_limit=a.real_nf),
                                             a.seed, call_budget=a.budget)
            row["nearest-first-real"] = dict(solved=bool(res and res.solved), time=round(secs, 3), attempts=att)
        if a.eager:
            res, secs, _, att = run_baseline("eager", problem.scene, problem.world, regions, problem.world.space, settings, a.seed)
            row["eager"] = dict(solved=bool(res and res.solved), time=round(secs if res and res.solved else a.eager_limit, 3),
                                attempts=att)
        print(json.dumps(row), flush=True)
        if a.jsonl:
            with open(a.jsonl, "a") as f:
                f.write(json.dumps(row) + "\n")
        rows.append(row)
    summary(rows, strategies)
    return 0


def summary(rows: list[dict], strategies: list[str]) -> None:
    """Medians, means, ratios against our first strategy, Mann-Whitney p of it against each other strategy."""
    def times(m):
        return [r[m]["time"] for r in rows if m in r]

    ours = strategies[0] if strategies else None
    methods = strategies + [m for m in ("nearest-first", "nearest-first-real", "eager") if any(m in r for r in rows)]
    for m in methods:
        t = times(m)
        solved = sum(1 for r in rows if m in r and (r[m].get("solved") or r[m].get("status") == "solved"))
        line = f"{m}: median {np.median(t):.3f} s, mean {np.mean(t):.3f} s, solved {solved}/{len(t)}"
        for extra in ("total", "setup"):  # the request as the user waits (planning, shortening, timing), world set-up
            more = [r[m][extra] for r in rows if m in r and extra in r[m]]
            line += f"; {extra} median {np.median(more):.3f} s" if more else ""
        if ours and m != ours and times(ours):
            line += (f"; {ours} faster by {np.median(t) / np.median(times(ours)):.1f}x at the median, "
                     f"{np.mean(t) / np.mean(times(ours)):.1f}x in the mean")
            if m in strategies:
                line += (f"; Mann-Whitney p two-sided {mann_whitney_p(times(ours), t):.3g}, "
                         f"one-sided ({ours} less) {mann_whitney_p(times(ours), t, 'less'):.3g}")
        print(line)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
