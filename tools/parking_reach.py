"""Which spots a car reaches on a parking scene, over many seeds (issue #17's parking_3 figures).

    PYTHONPATH=. python3 tools/parking_reach.py yaml_scenes/parking_3.yaml --seeds 50 --kinematics reeds-shepp

Prints, per strategy, the solve rate, the spots reached (with counts), and mean time / gear changes.
Seeds are 0..N-1; the scene's time limit unless --time-limit.
"""

from __future__ import annotations

import argparse
import collections
import statistics

from lazyground import api
from lazyground.drake.world import DrakeWorld
from lazyground.scene import load_scene
from lazyground.settings import Strategy


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--first-seed", type=int, default=0)
    ap.add_argument("--kinematics", default=None)
    ap.add_argument("--strategies", default=Strategy.REWARD_PENALTY.value)
    ap.add_argument("--time-limit", type=float, default=None)
    ap.add_argument("--request", default=None)
    args = ap.parse_args()
    scene = load_scene(args.scene)
    request = args.request or scene.expect[0].request
    world = DrakeWorld(scene, visual=False)
    for strategy in args.strategies.split(","):
        spots, times, cusps, solved = collections.Counter(), [], [], 0
        for seed in range(args.first_seed, args.first_seed + args.seeds):
            r = api.plan(scene, request, seed=seed, world=world, strategy=strategy, kinematics=args.kinematics,
                         time_limit=args.time_limit)
            times.append(r.time_s)
            if r.result.solved:
                solved += 1
                spots[r.chosen_object] += 1
                cusps.append(r.cusps or 0)
        mean_cusps = f"{statistics.mean(cusps):.1f}" if cusps else "-"
        print(f"{scene.name} {r.settings.planner.kinematics} {strategy}: solved {solved}/{args.seeds}, "
              f"mean time {statistics.mean(times):.2f} s (max {max(times):.2f}), mean gear changes {mean_cusps}; "
              f"reached {dict(sorted(spots.items()))}")


if __name__ == "__main__":
    main()
