"""Issue #33, arm racks: eager all-goal IK's up-front pass alone, per layout, on CPU seconds.

Eager (lazyground.bench.baselines.EagerSource) samples every goal region until it yields a valid sample or is given
up, then plans once with those samples and never samples again. Its pass is replayed here with the planner's own
generator (default_rng(seed), untouched before the first draw): the pass's CPU seconds bound eager's time from below,
and a layout whose pass yields no valid sample of the reachable can is one eager cannot solve at any time limit
(every other can is unreachable by construction, tests/drake/test_families_reach.py).

Usage (from the repository root):
  PYTHONPATH=. python3 tools/rack_eager_pass.py ROBOT N LAYOUTS [--seed 0] [--jsonl OUT.jsonl]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

import lazyground.planning.stop as stop_module
from lazyground.bench.baselines import EagerSource
from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import REACHABLE, can_kinds
from lazyground.bench.runner import load_problem
from lazyground.planning.stop import StopCondition
from tools.rack_targets import _layouts


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("robot")
    p.add_argument("n", type=int)
    p.add_argument("layouts", type=_layouts)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--jsonl")
    a = p.parse_args(argv)
    stop_module.CLOCK = time.process_time
    for lay in a.layouts:
        key = f"rack:{a.robot}:{a.n}:1:{lay}"
        kinds = can_kinds(generate(parse_key(key)))
        problem = load_problem(key)
        regions, _ = problem.ground()
        source = EagerSource(regions, problem.world)
        t0 = stop_module.CLOCK()
        samples = source.draw(10, np.random.default_rng(a.seed), StopCondition.after(None))
        secs = stop_module.CLOCK() - t0
        by_kind: dict[str, int] = {}
        for s in samples:
            k = kinds[regions[s.region].object]
            by_kind[k] = by_kind.get(k, 0) + 1
        row = dict(key=key, seed=a.seed, clock="cpu", pass_s=round(secs, 2), attempts=sum(st.attempts for st in source.stats),
                   samples=len(samples), by_kind=by_kind, reachable_sampled=by_kind.get(REACHABLE, 0) > 0)
        print(json.dumps(row), flush=True)
        if a.jsonl:
            with open(a.jsonl, "a") as f:
                f.write(json.dumps(row) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
