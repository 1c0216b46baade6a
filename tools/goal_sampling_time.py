"""Goal sampling's cost per request (#31): CPU ms of the goal-source draws, IK attempts, samples drawn.

Run from the checkout's root (cwd comes first on sys.path); the same script measures another checkout from its root::

    nice python3 tools/goal_sampling_time.py                     # Fetch scenes + panda/ur5e tabletops, seeds 0-9
    nice python3 tools/goal_sampling_time.py --scene fetch_cans_1 --seeds 20 --cprofile 30
    cd /path/to/other/checkout && nice python3 /path/to/this/tools/goal_sampling_time.py

Per scene (the world prebuilt, one warm-up request; ``api.plan`` with the scene's defaults), medians over the
seeds: the process (CPU) time inside the goal source's ``draw`` calls (load barely moves it), the report's
``goal_sampling_s`` (wall), the request's CPU time, IK attempts and valid samples per request, and the solved
count. ``--cprofile N`` prints the N functions with the most own CPU time inside the draws.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import statistics
import sys
import time
from pathlib import Path

SCENES = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3", "panda_tabletop", "ur5e_tabletop")


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", action="append", help=f"a bundled scene (default: {', '.join(SCENES)})")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--cprofile", type=int, default=0, metavar="N")
    args = p.parse_args()
    sys.path.insert(0, str(Path.cwd()))
    from lazyground import api, goals
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    prof = cProfile.Profile(time.process_time) if args.cprofile else None
    spent = {"cpu": 0.0, "attempts": 0, "valid": 0}
    draw = goals.RoundRobinGoalSource.draw

    def timed_draw(self, n, rng, stop):
        t0, a0, v0 = time.process_time(), self.total_attempts, self.total_valid
        if prof is not None:
            prof.enable()
        try:
            return draw(self, n, rng, stop)
        finally:
            if prof is not None:
                prof.disable()
            spent["cpu"] += time.process_time() - t0
            spent["attempts"] += self.total_attempts - a0
            spent["valid"] += self.total_valid - v0

    goals.RoundRobinGoalSource.draw = timed_draw
    print(f"median over seeds 0-{args.seeds - 1} (checkout {Path.cwd()}):")
    print(f"{'scene':16} {'IK cpu ms':>9} {'IK wall ms':>10} {'req cpu ms':>10} {'attempts':>8} {'valid':>6} solved")
    for name in args.scene or SCENES:
        scene = load_scene(name)
        world = DrakeWorld(scene, visual=False)
        request = scene.expect[0].request
        api.plan(scene, request, seed=1000, world=world)  # warm-up: first-call costs are not a request's
        rows = []
        for seed in range(args.seeds):
            spent.update(cpu=0.0, attempts=0, valid=0)
            t0 = time.process_time()
            report = api.plan(scene, request, seed=seed, world=world)
            rows.append(dict(spent, req=time.process_time() - t0, wall=report.result.goal_sampling_s,
                             solved=report.result.status.value == "solved"))
        med = {k: statistics.median(r[k] for r in rows) for k in ("cpu", "wall", "req", "attempts", "valid")}
        print(f"{name:16} {med['cpu'] * 1e3:9.1f} {med['wall'] * 1e3:10.1f} {med['req'] * 1e3:10.1f} {med['attempts']:8.0f} "
              f"{med['valid']:6.0f} {sum(r['solved'] for r in rows)}/{len(rows)}", flush=True)
    if prof is not None:
        out = io.StringIO()
        pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(args.cprofile)
        print(out.getvalue())
    return 0


if __name__ == "__main__":
    sys.exit(main())
