"""IK goal sampling A/B: the batch solver against SNOPT on the same seeds, in CPU time (#19).

    python3 tools/ik_ab.py --scenes fetch_cans_1,fetch_cans_2,fetch_boxes_3 --seeds 20

Per scene and seed, each solver draws goal samples as the default two-tree planner does
(``initial_goal_samples`` first, then ``--resamples`` draws of ``resample_count``) from a
fresh source over one shared world; the solvers alternate seed by seed so that machine load
hits both alike. A solver may carry IKSettings overrides, e.g. ``--solvers batch,batch:hand_check=0``
(an A/B of one setting). Prints per scene and solver: median CPU ms per valid goal sample (failed
attempts included), valid samples per attempt, IK solves and their success rate, collision
checks per valid sample.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import grounding  # noqa: E402
from lazyground.api import planner_settings  # noqa: E402
from lazyground.drake.ik import DEFAULT_IK_SETTINGS, IKGoalSource  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning.stop import StopCondition  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

SCENES = Path(__file__).resolve().parents[1] / "yaml_scenes"


def one_run(world, regions, settings, ik_settings, seed: int, resamples: int) -> dict:
    source = IKGoalSource(regions, world, ik_settings)
    rng = np.random.default_rng(seed)
    checks0 = world.checks
    t0 = time.process_time()
    samples = source.draw(settings.initial_goal_samples, rng, StopCondition())
    for _ in range(resamples):
        samples += source.draw(settings.resample_count, rng, StopCondition())
    cpu = time.process_time() - t0
    return {"cpu": cpu, "valid": len(samples), "attempts": sum(st.attempts for st in source.stats),
            "solves": source.counters.solves, "ik_ok": source.counters.successes, "checks": world.checks - checks0}


def ik_settings(spec: str, batch_attempts: int):
    """IKSettings for a solver spec "name[:field=value+...]" (values as the field's type; 0/1 for booleans)."""
    name, _, overrides = spec.partition(":")
    out = replace(DEFAULT_IK_SETTINGS, solver=name, attempt_budget=None, batch_attempts=batch_attempts)
    for item in filter(None, overrides.split("+")):
        key, value = item.split("=")
        kind = type(getattr(out, key))
        out = replace(out, **{key: bool(int(value)) if kind is bool else kind(value)})
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", default="fetch_cans_1,fetch_cans_2,fetch_boxes_3")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--resamples", type=int, default=5)
    ap.add_argument("--solvers", default="snopt,batch")
    ap.add_argument("--batch-attempts", type=int, default=DEFAULT_IK_SETTINGS.batch_attempts)
    args = ap.parse_args(argv)
    print("| scene | solver | runs | median CPU ms / goal sample | valid / attempt | IK solves / sample | IK success | checks / sample |")
    print("|---|---|---|---|---|---|---|---|")
    for name in args.scenes.split(","):
        scene = load_scene(SCENES / f"{name}.yaml")
        world = DrakeWorld(scene, visual=False)
        request = scene.expect[0].request
        regions = grounding.ground(request, scene).goal_regions
        settings = planner_settings(scene)
        solvers = args.solvers.split(",")
        runs = {s: [] for s in solvers}
        for s in solvers:  # build the reach map and warm the caches outside the timed runs
            one_run(world, regions, settings, ik_settings(s, args.batch_attempts), 10**6, 0)
        for seed in range(args.seeds):
            for s in solvers:
                runs[s].append(one_run(world, regions, settings, ik_settings(s, args.batch_attempts), seed, args.resamples))
        for s in solvers:
            rs = runs[s]
            total = {k: sum(r[k] for r in rs) for k in rs[0]}
            med = statistics.median(1e3 * r["cpu"] / r["valid"] for r in rs if r["valid"])
            print(f"| {name} | {s} | {len(rs)} | {med:.1f} | {total['valid'] / total['attempts']:.3f} | "
                  f"{total['solves'] / total['valid']:.1f} | {total['ik_ok'] / total['solves']:.2f} | {total['checks'] / total['valid']:.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
