"""Rates of several-object requests over seeds (issue #30): picking up several (stow, then hold),
packing on a narrow ledge (uniform placements against packed), and backtracking.

Run from anywhere (the script's checkout comes first on sys.path)::

    nice python3 tools/several_steps.py --seeds 20

Each row: the request, its scene and settings, runs solved of seeds, median planning seconds, the
seeds that backtracked. Every run is bounded by ``max_iterations`` per step (the time limit is a
backstop), so a seed's outcome does not depend on the machine's load; the seconds do.
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from lazyground import api  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402

ROWS = [  # scene, request, max_iterations per step, settings
    ("yaml_scenes/fetch_cans_1.yaml", "pick up two cans", 12000, {}),
    ("tests/data/scenes/panda_stow.yaml", "pick up all the red cans", 4000, {}),
    ("tests/data/scenes/panda_stow.yaml", "pick up both cans", 4000, {}),
    ("tests/data/scenes/panda_stow.yaml", "grab a couple of boxes", 4000, {}),
    ("tests/data/scenes/panda_pack.yaml", "put all the cups on the ledge", 4000, {"placement_draws": 1, "backtracks": 0}),
    ("tests/data/scenes/panda_pack.yaml", "put all the cups on the ledge", 4000, {"backtracks": 0}),
    ("tests/data/scenes/panda_pack.yaml", "put all the cups on the ledge", 4000, {"placement_draws": 1}),
    ("tests/data/scenes/panda_pack.yaml", "put all the cups on the ledge", 4000, {}),
]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 per row (default 10)")
    args = parser.parse_args(argv)
    print("| scene | request | settings | solved | median s | backtracked (seeds) |")
    print("| --- | --- | --- | --- | --- | --- |")
    for path, request, cap, settings in ROWS:
        scene = load_scene(ROOT / path)
        solved, seconds, back = 0, [], []
        for seed in range(args.seeds):
            r = api.plan(scene, request, seed=seed, max_iterations=cap, time_limit=600.0, **settings)
            solved += r.result.solved
            seconds.append(r.time_s)
            if any("backtracked" in n for n in r.notes):
                back.append(seed)
        label = ", ".join(f"{k}={v}" for k, v in settings.items()) or "defaults"
        print(f"| {scene.name} | {request} | {label} | {solved}/{args.seeds} | {statistics.median(seconds):.2f} | "
              f"{', '.join(map(str, back)) or '-'} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
