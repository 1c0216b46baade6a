"""Per-region IK goal sampling and planning figures for the Fetch scenes (docs/fetch.md).

    python3 tools/fetch_scene_report.py yaml_scenes/fetch_cans_1.yaml "pick up a can" --attempts 20
    python3 tools/fetch_scene_report.py yaml_scenes/fetch_cans_2.yaml "pick up a can" --plan-seeds 10 --time-limit 30

Prints, per goal region: IK attempts, valid goal samples, failure reasons and
time per solve; then, with --plan-seeds, planning success and time per
strategy and goal bias (each returned path re-checked at step / 100).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.drake.ik import IKGoalSource  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning.rrt import path_is_valid  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402


def region_report(scene, world, request: str, attempts: int, seed: int) -> list[str]:
    g = grounding.ground(request, scene)
    source = IKGoalSource(g.goal_regions, world, give_up_after=10**9)
    rng = np.random.default_rng(seed)
    lines = ["| region | attempts | valid | failures | IK solves | IK ok | ms/solve |", "|---|---|---|---|---|---|---|"]
    t0 = time.perf_counter()
    for j, st in enumerate(source.stats):  # every region gets the same number of attempts
        for _ in range(attempts):
            a0 = time.perf_counter()
            sample, reason = source.attempt(j, rng, a0 + 60.0)
            st.attempts += 1
            st.time += time.perf_counter() - a0
            if sample is None:
                st.fail(reason)
            else:
                st.valid += 1
    for region, st, c in zip(source.regions, source.stats, source.region_counters):
        fails = ", ".join(f"{k} {v}" for k, v in sorted(st.failures.items())) or "-"
        ms = f"{1e3 * c.time / c.solves:.1f}" if c.solves else "-"
        lines.append(f"| {region.id} | {st.attempts} | {st.valid} | {fails} | {c.solves} | {c.successes} | {ms} |")
    all_ = source.counters.to_json()
    lines.append(f"\nall regions: {sum(s.attempts for s in source.stats)} attempts, {sum(s.valid for s in source.stats)} valid, "
                 f"IK {all_['successes']}/{all_['solves']} solves succeeded, {all_['mean_solve_ms']} ms per solve "
                 f"(success {all_['mean_success_ms']} ms, failure {all_['mean_failure_ms']} ms); {time.perf_counter() - t0:.2f} s")
    return lines


def plan_report(scene, world, request: str, seeds: int, time_limit: float, configs) -> list[str]:
    lines = ["| strategy | bias | solved | mean s | median s | max s | goal sampling s (mean) | reached |", "|---|---|---|---|---|---|---|---|"]
    for strategy, bias in configs:
        times, sampling, reached, solved = [], [], Counter(), 0
        for seed in range(seeds):
            r = api.plan(scene, request, seed=seed, world=world, strategy=strategy, goal_bias=bias, time_limit=time_limit)
            res = r.result
            times.append(r.time_s)
            sampling.append(res.goal_sampling_s)
            if res.solved:
                assert path_is_valid(world.space, world, res.path, r.settings.planner.step_size / 100) < 0, f"seed {seed}: invalid path"
                solved += 1
                reached[res.goal_region.id] += 1
        lines.append(f"| {strategy} | {bias:g} | {solved}/{seeds} | {statistics.mean(times):.2f} | {statistics.median(times):.2f} | "
                     f"{max(times):.2f} | {statistics.mean(sampling):.2f} | {', '.join(f'{k} x{v}' for k, v in sorted(reached.items())) or '-'} |")
        print(lines[-1], flush=True)
    return lines


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scene")
    p.add_argument("request")
    p.add_argument("--attempts", type=int, default=20, help="IK attempts per region")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--plan-seeds", type=int, default=0)
    p.add_argument("--time-limit", type=float, default=30.0)
    p.add_argument("--configs", default="reward-penalty:0.05,consecutive:0.05,reward-penalty:0.5,consecutive:0.5")
    args = p.parse_args(argv)
    scene = load_scene(args.scene)
    world = DrakeWorld(scene)
    print(f"## {scene.name}: {args.request!r}\n")
    if args.attempts:
        print("\n".join(region_report(scene, world, args.request, args.attempts, args.seed)), flush=True)
    if args.plan_seeds:
        configs = [(c.split(":")[0], float(c.split(":")[1])) for c in args.configs.split(",")]
        print(f"\nplanning, {args.plan_seeds} seeds, time limit {args.time_limit:g} s:\n")
        print("\n".join(plan_report(scene, world, args.request, args.plan_seeds, args.time_limit, configs)[:2]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
