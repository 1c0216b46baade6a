"""Where a collision check's time goes (#31): the search's checks on the Fetch scenes, replayed, CPU time per kind
of check split into the compiled kernel, SceneGraph's fallback for the pairs it leaves open, and the Python glue.

Run from the checkout's root (cwd comes first on sys.path; works on checkouts from before the edge kernel)::

    nice python3 tools/check_split.py                  # seeds 0-4, ~1-2 minutes quiet
    nice python3 tools/check_split.py --seeds 10 --reps 5
    nice python3 tools/check_split.py --scenes rack:fetch:64:1:0 --seeds 3   # a generated rack (#33)

It plans each scene's first request at seeds 0..N-1 (world prebuilt, one warm-up request) and records every
check the search makes (goal sampling's are the IK's, not counted here, as in the report's collision_s), with
the kernel calls and SceneGraph queries each makes. Then it replays them ``--reps`` times and keeps the fastest:
all the calls of a kind, their kernel calls alone, their SceneGraph queries alone; glue is the rest. "counted"
is what ``collision_checks`` counts (a batch's rows one each), so the last column is the report's us/check in CPU
time. The replayed answers must equal the recorded ones (checked).
"""

from __future__ import annotations

import argparse
import collections
import sys
import time
from pathlib import Path

import numpy as np

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")
KINDS = ("config_free", "config_unpadded_free", "configs_free", "configs_free_along", "edge_free", "edge_fraction",
         "edge_part_free")
clock = time.process_time


def record(name: str, seeds: int):
    """(checker, [(kind, args, answer, counted, kernel calls, SceneGraph calls)]) of the search's checks."""
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.planning import search as se
    from lazyground.scene import load_scene

    if name.startswith("rack:"):  # a generated rack (#33): its world and request as the bench loads them
        from lazyground.bench.runner import load_problem
        from lazyground.settings import Algorithm, Strategy

        problem = load_problem(name)
        scene, world, request = problem.scene, problem.world, problem.request
        options = dict(strategy=Strategy.COVER.value, algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=30)  # as tools/rack_split.py plans
    else:
        scene = load_scene(name)
        world = DrakeWorld(scene, visual=False)
        request = scene.expect[0].request
        options = {}
    api.plan(scene, request, seed=1000, world=world, **options)
    c = world.checker
    state = dict(search=False, sampling=0, depth=0, log=None)
    calls, undo = [], []

    def wrap(owner, attr, kind):
        inner = getattr(owner, attr)
        undo.append((owner, attr, owner.__dict__.get(attr)))

        def f(*a, **k):
            if state["log"] is not None:
                state["log"].append((kind, inner, a, k))
            return inner(*a, **k)
        setattr(owner, attr, f)

    for attr in ("certify_one", "certify", "sweep", "first_open"):
        wrap(c.compiled, attr, "kernel")
    for attr in ("_certify_one", "_edge_open"):  # the kernels the checker binds (edge3 on)
        if hasattr(c, attr):
            wrap(c, attr, "kernel")
    checker_module = sys.modules[type(c).__module__]
    for attr in ("edge_call", "config_call"):  # the kernels it calls on its packed arrays (kern4 on)
        if hasattr(checker_module, attr):
            wrap(checker_module, attr, "kernel")
    wrap(c, "_open_free", "scenegraph")
    for kind in KINDS:
        inner = getattr(c, kind)
        undo.append((c, kind, None))

        def top(*a, _inner=inner, _kind=kind, **k):
            if state["depth"] or not state["search"] or state["sampling"]:
                return _inner(*a, **k)
            state["depth"], state["log"], n0 = 1, [], c.checks
            try:
                out = _inner(*a, **k)
            finally:
                state["depth"], log, state["log"] = 0, state["log"], None
            calls.append((_kind, _inner, [np.array(x) if isinstance(x, np.ndarray) else x for x in a], k,
                           np.asarray(out).tolist(), c.checks - n0, log))
            return out
        setattr(c, kind, top)
    search_init, draw, result = se.Search.__init__, se.Search.draw, se.Search.result

    def s_init(self, *a, **k):
        state["search"] = True
        return search_init(self, *a, **k)

    def s_draw(self, *a, **k):
        state["sampling"] += 1
        try:
            return draw(self, *a, **k)
        finally:
            state["sampling"] -= 1

    def s_result(self, *a, **k):
        state["search"] = False
        return result(self, *a, **k)

    se.Search.__init__, se.Search.draw, se.Search.result = s_init, s_draw, s_result
    try:
        for seed in range(seeds):
            api.plan(scene, request, seed=seed, world=world, **options)
    finally:
        se.Search.__init__, se.Search.draw, se.Search.result = search_init, draw, result
        for owner, attr, old in undo:  # the replay runs the checker's own code
            if old is None:
                owner.__dict__.pop(attr, None)
            else:
                setattr(owner, attr, old)
    return c, calls


def fastest(items, reps: int) -> float:
    best = np.inf
    for _ in range(reps):
        t0 = clock()
        for f, a, k in items:
            f(*a, **k)
        best = min(best, clock() - t0)
    return best


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--reps", type=int, default=3)
    p.add_argument("--scenes", default=",".join(FETCH))
    args = p.parse_args()
    sys.path.insert(0, str(Path.cwd()))
    print("CPU us per call (kernel + SceneGraph + glue) and per counted check, search phase, fastest of", args.reps)
    for name in args.scenes.split(","):
        c, calls = record(name, args.seeds)
        by = collections.defaultdict(list)
        for call in calls:
            by[call[0]].append(call)
        total = counted = 0.0
        print(f"{name} (seeds 0-{args.seeds - 1}):")
        for kind, group in by.items():
            for _, f, a, k, answer, _, _ in group:
                assert np.asarray(f(*a, **k)).tolist() == answer, (kind, "answer differs from the recorded one")
            t = fastest([(f, a, k) for _, f, a, k, _, _, _ in group], args.reps)
            kern = fastest([(g, a, k) for call in group for kd, g, a, k in call[6] if kd == "kernel"], args.reps)
            sg = fastest([(g, a, k) for call in group for kd, g, a, k in call[6] if kd == "scenegraph"], args.reps)
            n, cnt = len(group), sum(call[5] for call in group)
            total, counted = total + t, counted + cnt
            print(f"  {kind:21} {n:6} calls {cnt:6} counted: per call {t / n * 1e6:7.2f} = {kern / n * 1e6:6.2f} kernel "
                  f"+ {sg / n * 1e6:5.2f} SceneGraph + {(t - kern - sg) / n * 1e6:6.2f} glue; per counted {t / cnt * 1e6:6.2f}")
        print(f"  all: {total * 1e3:.1f} ms CPU over {counted:.0f} counted checks: {total / max(counted, 1) * 1e6:.2f} us per check",
              flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
