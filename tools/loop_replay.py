"""The planner loop's own time per iteration, checks and goal sampling replayed from a record (#31, Deliver 2).

Run from the checkout's root (cwd comes first on sys.path)::

    nice python3 tools/loop_replay.py                      # Fetch scenes, seeds 0-4, 20 replays each
    nice python3 tools/loop_replay.py --scenes fetch_boxes_3 --seeds 10 --replays 50

Each seed is planned once for real (``api.plan`` on a prebuilt world) while the checker's answers and the
goal source's samples (with the generator's state after each draw) are recorded; the search is then run
again ``--replays`` times against the record: the same iterations, nodes and path, with every collision
check and IK draw a list lookup. Its CPU time (``time.process_time``, so a busy machine's waits do not count)
per iteration is the loop's overhead outside checks and goal sampling: nearest neighbours, steering, tree
and strategy bookkeeping, Python calls per edge. Printed per scene: the median over seeds of the fastest
replay (the least disturbed), and the search's real figures for scale. A replay that does not end as the
real run did is reported (the record would not fit the code).
"""

from __future__ import annotations

import argparse
import copy
import statistics
import sys
import time
from pathlib import Path

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")
ANSWERS = ("config_free", "config_unpadded_free", "configs_free", "edge_free", "edge_fraction")


class Recorder:
    """A checker or goal source whose answers are logged in call order (record) or read back (replay)."""

    def __init__(self, inner=None, log: list | None = None):
        self._inner, self._log, self._replay = inner, [] if log is None else log, log is not None
        self._at = 0
        self.check_time = self.checks = 0

    def _answer(self, name, *args):
        if self._replay:
            out = self._log[self._at]
            self._at += 1
            return out
        out = getattr(self._inner, name)(*args)
        self._log.append(copy.deepcopy(out))
        return out

    def __getattr__(self, name):
        if name in ANSWERS:
            return lambda *args, _n=name: self._answer(_n, *args)
        raise AttributeError(name)


class GoalRecorder(Recorder):
    """Goal draws: the samples and the generator's state after each (a replay restores it)."""

    def __init__(self, inner=None, log: list | None = None, regions=(), stats=()):
        super().__init__(inner, log)
        self.regions = inner.regions if inner is not None else regions
        self.stats = inner.stats if inner is not None else stats
        self.sample_time = 0.0

    @property
    def total_attempts(self):
        return self._answer("total_attempts_")

    def total_attempts_(self):
        return getattr(self._inner, "total_attempts", None)

    def exhausted(self):
        return self._answer("exhausted_")

    def exhausted_(self):
        return self._inner.exhausted()

    def draw(self, n, rng, stop):
        if self._replay:  # (the log is a fresh copy per replay: nothing is copied while the replay is timed)
            samples, state = self._log[self._at]
            self._at += 1
            rng.bit_generator.state = state
            return samples
        out = self._inner.draw(n, rng, stop)
        self._log.append((copy.deepcopy(out), copy.deepcopy(rng.bit_generator.state)))
        return out


def record(scene_name: str, seed: int, world, scene) -> dict:
    """One real plan, its solve() call's arguments and logs."""
    from lazyground import api
    from lazyground.planning import rrt

    rec = {}
    real_solve = rrt.solve

    def recording(space, checker, goals, start, settings, rng, seed=None, keep_tree=False, stop=None):
        if "space" in rec:  # (a later search of the same request, e.g. an anytime improvement: the first is replayed)
            return real_solve(space, checker, goals, start, settings, rng, seed, keep_tree, stop)
        ck, gs = Recorder(checker), GoalRecorder(goals)
        rec.update(space=space, start=start.copy(), settings=settings, state=copy.deepcopy(rng.bit_generator.state),
                   seed=seed, checks=ck._log, goals=gs._log, regions=goals.regions, stats=copy.deepcopy(goals.stats))
        r = real_solve(space, ck, gs, start, settings, rng, seed, keep_tree, stop)
        rec["iterations"], rec["path"] = r.iterations, r.path
        return r

    targets = [m for k, m in list(sys.modules.items()) if k.startswith("lazyground") and getattr(m, "solve", None) is real_solve]
    for m in targets:
        m.solve = recording
    try:
        report = api.plan(scene, scene.expect[0].request, seed=seed, world=world)
    finally:
        for m in targets:
            m.solve = real_solve
    rec["report"] = report
    return rec


def replay(rec: dict) -> tuple[float, bool]:
    """(CPU seconds of one replayed solve, whether it ended as the recorded run)."""
    import numpy as np

    from lazyground.planning import rrt
    from lazyground.planning.stop import StopCondition

    ck = Recorder(log=rec["checks"])
    gs = GoalRecorder(log=copy.deepcopy(rec["goals"]), regions=rec["regions"], stats=copy.deepcopy(rec["stats"]))
    rng = np.random.default_rng()
    rng.bit_generator.state = copy.deepcopy(rec["state"])
    stop = StopCondition.after(1e9, max_iterations=rec["settings"].max_iterations)
    t0 = time.process_time()
    r = rrt.solve(rec["space"], ck, gs, rec["start"], rec["settings"], rng, rec["seed"], False, stop)
    dt = time.process_time() - t0
    same = r.iterations == rec["iterations"] and (
        (r.path is None) == (rec["path"] is None) and (r.path is None or np.array_equal(r.path, rec["path"])))
    return dt, same


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", default=",".join(FETCH))
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--replays", type=int, default=20)
    args = p.parse_args()
    sys.path.insert(0, str(Path.cwd()))
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    print(f"{'scene':15} {'iters':>6} {'loop us/it':>10} {'loop ms/run':>11} {'search-IK ms':>12} {'replays ok':>10}")
    for name in args.scenes.split(","):
        scene = load_scene(name)
        world = DrakeWorld(scene, visual=False)
        record(name, 1000, world, scene)  # warm-up
        per_it, per_run, search, its, ok = [], [], [], [], 0
        for seed in range(args.seeds):
            rec = record(name, seed, world, scene)
            r = rec["report"].result
            best = float("inf")
            for _ in range(args.replays):
                dt, same = replay(rec)
                best, ok = min(best, dt), ok + same
            per_it.append(best / max(rec["iterations"], 1) * 1e6)
            per_run.append(best * 1e3)
            search.append((r.time_s - r.goal_sampling_s) * 1e3)
            its.append(rec["iterations"])
        med = statistics.median
        print(f"{name:15} {med(its):6.0f} {med(per_it):10.1f} {med(per_run):11.2f} {med(search):12.1f} "
              f"{ok:>5}/{args.seeds * args.replays}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
