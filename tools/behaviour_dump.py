"""Dump what a checkout plans, seed for seed, to compare two checkouts ("behaviour unchanged", #35).

Run from the root of the checkout to test (cwd comes first on sys.path)::

    nice python3 tools/behaviour_dump.py --out /tmp/after.json
    (cd /tmp/before && nice python3 /work/.../tools/behaviour_dump.py --out /tmp/before.json)
    python3 tools/behaviour_dump.py --diff /tmp/before.json /tmp/after.json

Rows whose status differs (a run the loaded machine's clock cut at the time limit in one checkout only) can be
run again in both with ``--recheck ROWS.json --time-limit 600``, which ends each run on its own.

It records (scene, strategy, seed, status, iterations, path length) for
``lazyground bench --table 1 --runs 50 --kinematics holonomic --jobs 1`` (its results.csv) and for
``api.plan`` on the three Fetch scenes of Table II at seeds 0-19 (each scene's first expectation:
its request, and its ``max_iterations`` and ``time_limit`` as in tests/scenes, IK attempts bounded by counts
as in tests/conftest.py, so a seed's outcome does not depend on the machine's load; the shortcut's 1 s budget raised to 600 s for the same reason). Each row
holds the raw (planner's) and the final (shortened) path length.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
import tempfile
from pathlib import Path

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")
CLOCKLESS_SHORTCUT = 600.0  # s: the shortcut ends by its attempts and patience, not by a loaded machine's clock


def bench_rows(runs: int) -> list[dict]:
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([sys.executable, "-m", "lazyground", "bench", "--table", "1", "--runs", str(runs),
                        "--kinematics", "holonomic", "--jobs", "1", "--out", out], check=True,
                       stdout=subprocess.DEVNULL)
        with open(Path(out) / "results.csv", newline="") as f:
            return [{"scene": r["scene"], "strategy": r["strategy"], "seed": int(r["seed"]), "status": r["status"],
                     "iterations": int(r["iterations"] or 0), "path_length": r["path_length"]} for r in csv.DictReader(f)]


def _ik_without_clock() -> None:
    """IK attempts bounded by counts, not the clock (as tests/conftest.py does): a loaded machine then cuts no attempt."""
    from dataclasses import replace

    try:
        from lazyground.drake.ik import settings as module  # since #35
    except ImportError:
        from lazyground.drake import ik as module  # before #35: one module
    module.DEFAULT_IK_SETTINGS = replace(module.DEFAULT_IK_SETTINGS, attempt_budget=None)


def fetch_rows(seeds: int, scenes=FETCH) -> list[dict]:
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    _ik_without_clock()
    rows = []
    for name in scenes:
        scene = load_scene(name)
        exp = scene.expect[0]
        caps = {k: getattr(exp, k) for k in ("max_iterations", "time_limit") if getattr(exp, k) is not None}
        caps["shortcut_time"] = CLOCKLESS_SHORTCUT
        world = DrakeWorld(scene)
        for seed in range(seeds):
            rows.append(_row(name, "api.plan", seed, api.plan(scene, exp.request, seed=seed, world=world, **caps)))
    return rows


def recheck_rows(keys: list[dict], time_limit: float) -> list[dict]:
    """Table I runs again through ``api.plan`` as the bench makes them, with a long time limit: a run the loaded
    machine's clock cut short in either checkout then ends on its own, the same way in both."""
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene
    from lazyground.settings import Algorithm

    rows, worlds = [], {}
    for k in keys:
        if k["scene"] not in worlds:
            scene = load_scene(k["scene"])
            worlds[k["scene"]] = (scene, DrakeWorld(scene))
        scene, world = worlds[k["scene"]]
        report = api.plan(scene, scene.expect[0].request, seed=k["seed"], world=world, strategy=k["strategy"], algorithm=Algorithm.RRT,
                          goal_bias=0.05, time_limit=time_limit, kinematics="holonomic", shortcut_time=CLOCKLESS_SHORTCUT)
        rows.append(_row(k["scene"], k["strategy"], k["seed"], report))
    return rows


def _row(scene: str, strategy: str, seed: int, report) -> dict:
    r, motion = report.result, report.motion
    return {"scene": scene, "strategy": strategy, "seed": seed, "status": r.status.value, "iterations": r.iterations,
            "raw_path_length": f"{motion.raw_length:.6f}" if motion is not None else "", "path_length": f"{r.path_length:.6f}"}


def diff(a_path: str, b_path: str) -> int:
    a, b = (json.loads(Path(p).read_text()) for p in (a_path, b_path))
    key = lambda r: (r["scene"], r["strategy"], r["seed"])  # noqa: E731
    bk = {key(r): r for r in b["rows"]}
    changed = [(r, bk.get(key(r))) for r in a["rows"] if bk.get(key(r)) != r]
    print(f"{len(a['rows'])} rows before, {len(b['rows'])} after; {len(changed)} differ")
    for old, new in changed[:20]:
        print(f"  {old} -> {new}")
    return 1 if changed or len(a["rows"]) != len(b["rows"]) else 0


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", help="write the JSON here")
    p.add_argument("--runs", type=int, default=50)
    p.add_argument("--seeds", type=int, default=20)
    p.add_argument("--diff", nargs=2, metavar=("BEFORE", "AFTER"))
    p.add_argument("--recheck", metavar="ROWS.json", help="re-run these Table I rows (scene, strategy, seed) with a long time limit")
    p.add_argument("--time-limit", type=float, default=600.0)
    p.add_argument("--fetch-only", action="store_true", help="only the Fetch scenes through api.plan")
    p.add_argument("--scenes", default=",".join(FETCH), help="the arm scenes run through api.plan (comma-separated; "
                   "e.g. panda_tabletop,ur5e_tabletop)")
    args = p.parse_args()
    if args.diff:
        return diff(*args.diff)
    sys.path.insert(0, str(Path.cwd()))
    if args.recheck:
        rows = recheck_rows(json.loads(Path(args.recheck).read_text()), args.time_limit)
        Path(args.out).write_text(json.dumps({"cwd": str(Path.cwd()), "rows": rows}, indent=0))
        print(f"wrote {len(rows)} rows to {args.out}")
        return 0
    rows = ([] if args.fetch_only else bench_rows(args.runs)) + fetch_rows(args.seeds, args.scenes.split(","))
    Path(args.out).write_text(json.dumps({"cwd": str(Path.cwd()), "rows": rows}, indent=0))
    print(f"wrote {len(rows)} rows to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
