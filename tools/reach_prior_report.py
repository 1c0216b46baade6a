"""What the reach prior drops on generated lots and bundled parking scenes, and what it costs (issue #33).

Per scene: the spots kept and dropped by kind (generated lots: reachable, barrier, gated, narrow; bundled
scenes: by the expectation's ``reachable`` list), the world build's and the prior's build seconds (medians
over ``--repeats`` fresh worlds, CPU seconds of this process: steadier than the wall clock on a busy machine), the grid's cells::

    PYTHONPATH=. python3 tools/reach_prior_report.py --scenes lot:8:2:0:576,lot:64:2:0:576,lot:256:2:0:576,lot:512:2:0:576,parking_1,parking_2,parking_3
"""

from __future__ import annotations

import argparse
import collections
import statistics
import sys
import time

import grounding
from lazyground.bench.families import generate, load_family_scene, parse_key
from lazyground.bench.families.lot import REACHABLE, spot_kinds
from lazyground.bundled import bundled_scene
from lazyground.drake.reach_prior import planar_reach
from lazyground.drake.world import DrakeWorld
from lazyground.scene import load_scene


def _scene(key: str):
    """(scene, spot -> kind) of a family key or a bundled parking scene."""
    if parse_key(key) is not None:
        return load_family_scene(key), spot_kinds(generate(parse_key(key)))
    scene = load_scene(bundled_scene(key) or key)
    reachable = set(scene.expect[0].reachable or ())
    return scene, {o.id: REACHABLE if o.id in reachable else "blocked" for o in scene.objects if not o.occupied}


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", default="lot:64:2:0:576,lot:512:2:0:576,parking_1,parking_2,parking_3")
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    import scipy.ndimage  # noqa: F401  (imported once per process: not the prior's cost per world)

    print("| scene | spots kept / dropped by kind | world build s | prior s | grounding s | cells |\n|---|---|---|---|---|---|")
    for key in a.scenes.split(","):
        scene, kinds = _scene(key)
        t0 = time.process_time()
        regions = grounding.ground("park", scene).goal_regions
        ground_s = time.process_time() - t0
        worlds, priors = [], []
        for _ in range(a.repeats):
            t0 = time.process_time()
            world = DrakeWorld(scene, visual=False)
            worlds.append(time.process_time() - t0)
            t0 = time.process_time()
            prior = planar_reach(world)
            priors.append(time.process_time() - t0)
        spots = collections.Counter()
        for obj in dict.fromkeys(r.object for r in regions):
            kept = any(prior.keeps(r) for r in regions if r.object == obj)
            spots[kinds[obj], "kept" if kept else "dropped"] += 1
        text = ", ".join(f"{k} {spots[k, 'kept']} / {spots[k, 'dropped']}" for k in sorted({k for k, _ in spots}))
        print(f"| {key} | {text} | {statistics.median(worlds):.3f} | {statistics.median(priors):.3f} | {ground_s:.3f} | "
              f"{prior.grid.labels.size:,} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
