"""What the reach prior drops on generated lots and racks and on bundled scenes, and what it costs (issue #33).

Per scene: the interpretations (spots, cans) kept and dropped by kind (generated lots: reachable, barrier, gated,
narrow; racks: reachable, window, caged, behind; bundled scenes: by the first expectation's ``reachable`` list),
the goal regions dropped (an arm's: how many of them by the reach bound alone, their box of ball centres beyond
the sphere the chain can stretch to), the world build's and the prior's build seconds (medians over ``--repeats``
fresh worlds, CPU seconds of this process: steadier than the wall clock on a busy machine), the grid's cells::

    PYTHONPATH=. python3 tools/reach_prior_report.py --scenes lot:8:2:0:576,lot:64:2:0:576,lot:256:2:0:576,lot:512:2:0:576,parking_1,parking_2,parking_3
    PYTHONPATH=. python3 tools/reach_prior_report.py --scenes rack:panda:4:1:0,rack:panda:64:1:0,rack:fetch:64:1:0,panda_tabletop
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
from lazyground.bench.families.rack import can_kinds
from lazyground.bundled import bundled_scene
from lazyground.drake.world import DrakeWorld
from lazyground.geometry import Pose
from lazyground.planning.reach_prior import pose_centre_box
from lazyground.scene import load_scene


def _scene(key: str):
    """(scene, request, object -> kind) of a family key or a bundled scene."""
    spec = parse_key(key)
    if spec is not None:
        scene = load_family_scene(key)
        if key.startswith("rack"):
            return scene, scene.expect[0].request, can_kinds(generate(spec))
        return scene, "park", spot_kinds(generate(spec))
    scene = load_scene(bundled_scene(key) or key)
    reachable = set(scene.expect[0].reachable or ())
    return scene, scene.expect[0].request, {o.id: REACHABLE if o.id in reachable else "blocked" for o in scene.objects}


def _by_reach(prior, region, attached=None) -> bool:
    """Whether an arm's prior drops ``region`` by the reach bound alone (one ball's centres all beyond its sphere)."""
    if not hasattr(prior, "balls") or not hasattr(region, "X_WR"):
        return False
    frame, X_ET = region.robot_target(Pose(), attached)
    lower, span, _ = region.unit_map()
    boxes = [pose_centre_box(region.X_WR.matrix(), region.X_SE.matrix() @ X_ET.matrix(), p, lower, span)
             for _, p in prior.balls(frame)]
    return any(b.beyond_reach(*box) for (b, _), box in zip(prior.balls(frame), boxes))


def _cells(prior) -> int:
    return sum(g.labels.size for g in ([prior.grid] if hasattr(prior, "grid") else prior.grids))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", default="lot:64:2:0:576,lot:512:2:0:576,parking_1,parking_2,parking_3")
    p.add_argument("--repeats", type=int, default=5)
    a = p.parse_args(argv)
    import scipy.ndimage  # noqa: F401  (imported once per process: not the prior's cost per world)

    print("| scene | kept / dropped by kind | regions dropped (by reach alone) | world build s | prior s | grounding s | cells |\n"
          "|---|---|---|---|---|---|---|")
    for key in a.scenes.split(","):
        scene, request, kinds = _scene(key)
        t0 = time.process_time()
        regions = grounding.ground(request, scene).goal_regions
        ground_s = time.process_time() - t0
        worlds, priors = [], []
        for _ in range(a.repeats):
            t0 = time.process_time()
            world = DrakeWorld(scene, visual=False)
            worlds.append(time.process_time() - t0)
            t0 = time.process_time()
            prior = world.reach_prior()
            priors.append(time.process_time() - t0)
        kept = {j for j, r in enumerate(regions) if prior.keeps(r)}
        objects = collections.Counter()
        for obj in dict.fromkeys(r.object for r in regions):
            mine = any(j in kept for j, r in enumerate(regions) if r.object == obj)
            objects[kinds.get(obj, "blocked"), "kept" if mine else "dropped"] += 1
        text = ", ".join(f"{k} {objects[k, 'kept']} / {objects[k, 'dropped']}" for k in sorted({k for k, _ in objects}))
        reach = sum(_by_reach(prior, r) for j, r in enumerate(regions) if j not in kept)
        print(f"| {key} | {text} | {len(regions) - len(kept)} of {len(regions)} ({reach}) | {statistics.median(worlds):.3f} | "
              f"{statistics.median(priors):.3f} | {ground_s:.3f} | {_cells(prior):,} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
