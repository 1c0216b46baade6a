"""The #31 target table in one command: Fetch requests as the user waits for them, time per check, the
per-iteration profile, and parking_1's Table I time.

Run from the checkout's root (cwd comes first on sys.path), on a quiet machine (~3-4 minutes)::

    nice python3 tools/target_table.py                 # seeds 0-9 on Fetch, 0-19 on parking_1
    nice python3 tools/target_table.py --seeds 20 --parking-seeds 40
    nice python3 tools/target_table.py --parking-only        # table 3 alone (~30 s quiet)
    cd /path/to/other/checkout && nice python3 /path/to/this/tools/target_table.py   # the same table on its code

Prints three tables:

1. per Fetch scene (the world prebuilt, one warm-up request; ``api.plan`` on the loaded Scene), medians:
   total_s (the report's: the call's wall time less the world build) and its split (grounding, search with
   its IK goal sampling shown apart, motion, rest), checks and time per check (collision_s / checks), against
   the targets 60 / 60 / 150 ms and 3 us;
2. ``lazyground bench --iteration-profile``'s table (lazyground/bench/iteration_profile.py);
3. parking_1 as Table I runs it (one-tree planner, reward-penalty, goal bias 0.05, holonomic): median
   planning time (grounding + search, the bench's time_s) and total_s.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")
TARGET_MS = {"fetch_cans_1": 60, "fetch_cans_2": 60, "fetch_boxes_3": 150}
TARGET_US_PER_CHECK = 3.0


def parking(seeds: int) -> dict:
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene
    from lazyground.settings import Algorithm, Strategy

    scene = load_scene("parking_1")
    world = DrakeWorld(scene, visual=False)
    request = scene.expect[0].request
    kw = dict(strategy=Strategy.REWARD_PENALTY, algorithm=Algorithm.RRT, goal_bias=0.05, kinematics="holonomic")
    api.plan(scene, request, seed=1000, world=world, **kw)
    cpu = time.process_time()
    reports = [api.plan(scene, request, seed=s, world=world, **kw) for s in range(seeds)]
    cpu = time.process_time() - cpu
    return dict(planning=statistics.median(r.time_s for r in reports), total=statistics.median(r.total_s for r in reports),
                solved=sum(r.result.solved for r in reports), runs=len(reports), cpu=cpu,
                iterations=sum(r.result.iterations for r in reports))


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seeds", type=int, default=10, help="Fetch seeds per scene (0..N-1)")
    p.add_argument("--parking-seeds", type=int, default=20)
    p.add_argument("--parking-only", action="store_true", help="only table 3 (Table I's parking_1)")
    args = p.parse_args()
    sys.path.insert(0, str(Path.cwd()))
    if args.parking_only:
        _print_parking(parking(args.parking_seeds), args.parking_seeds)
        return 0
    sys.path.insert(1, str(Path(__file__).resolve().parent))
    import request_profile

    try:
        from lazyground.bench import iteration_profile
    except ImportError:  # a checkout from before the profile (#31's "before"): this tool's own copy, on its code
        import importlib.util

        path = Path(__file__).resolve().parents[1] / "lazyground/bench/iteration_profile.py"
        spec = importlib.util.spec_from_file_location("iteration_profile", path)
        iteration_profile = importlib.util.module_from_spec(spec)
        sys.modules["iteration_profile"] = iteration_profile
        spec.loader.exec_module(iteration_profile)

    t0 = time.perf_counter()
    print(f"Fetch requests, median over seeds 0-{args.seeds - 1}, ms (world prebuilt; total = api.plan wall less world build):")
    print(f"{'scene':15} {'total':>7} {'target':>7} {'ground':>7} {'search':>7} {'(IK)':>7} {'motion':>7} {'rest':>7} "
          f"{'checks':>7} {'us/chk':>7} solved")
    for name in FETCH:
        m = request_profile.profile_scene(name, args.seeds, by_path=False, top=0)
        print(f"{name:15} {m['total'] * 1e3:7.1f} {TARGET_MS[name]:7d} {m['grounding'] * 1e3:7.1f} {m['search'] * 1e3:7.1f} "
              f"{m['ik'] * 1e3:7.1f} {m['motion'] * 1e3:7.1f} {m['rest'] * 1e3:7.1f} {m['checks']:7.0f} "
              f"{m['per_check'] * 1e6:7.1f} {m['solved']}/{args.seeds}", flush=True)
    print(f"(target per check: {TARGET_US_PER_CHECK:g} us)\n")
    profiles = [iteration_profile.profile_scene(name, range(args.seeds)) for name in FETCH]
    print(iteration_profile.report(profiles), flush=True)
    _print_parking(parking(args.parking_seeds), args.parking_seeds)
    print(f"({time.perf_counter() - t0:.0f} s)", file=sys.stderr)
    return 0


def _print_parking(park: dict, seeds: int) -> None:
    print(f"parking_1, Table I settings (rrt, reward-penalty, bias 0.05, holonomic), seeds 0-{seeds - 1}: "
          f"median planning {park['planning'] * 1e3:.1f} ms, total {park['total'] * 1e3:.1f} ms, "
          f"solved {park['solved']}/{park['runs']}; CPU of all {park['runs']} plans {park['cpu']:.2f} s "
          f"({park['iterations']} iterations)", flush=True)


if __name__ == "__main__":
    sys.exit(main())
