"""Plan every MoveIt corpus scene with default settings over seeds; print a table per scene (#15).

    PYTHONPATH=$PWD python3 tools/corpus_report.py --seeds 10            # 30 s limit (the robot's default)
    PYTHONPATH=$PWD python3 tools/corpus_report.py --seeds 3 --only bookshelf_cans
    PYTHONPATH=$PWD python3 tools/corpus_report.py --seeds 10 --ab       # issue 34: before / after in one run

Times are grounding + planning per run (the world is built once per scene; its set-up is a column).
With ``--ab``, every run is made twice, alternating which goes first: "before" without the angled
grasps and with uniform goal draws (``goal_learning`` 0; the draws are then those of the code before
issue 34's item 4), "after" with the defaults; the table gives both and the ratio of their medians.
``--ab`` also plans the bundled Fetch scenes (fetch_cans_1, fetch_cans_2, fetch_boxes_3).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

from lazyground.bench.moveit_corpus import Run, corpus_entries, import_entry, run_entry, table


def without_angled(scene):
    """``scene`` with the bundled grasp types less their angled (``tilt``) templates."""
    from lazyground.scene.types import default_types

    types = {t: {**d, "pick": [s for s in d["pick"] if "tilt" not in s]} for t, d in default_types().items()
             if any("tilt" in s for s in d.get("pick", []))}
    return replace(scene, grasp_types={**types, **(scene.grasp_types or {})})


BUNDLED_FETCH = {"fetch_cans_1": "pick up a can", "fetch_cans_2": "pick up a can", "fetch_boxes_3": "pick up a box"}


def ab_scene(name: str, scene, request: str, seeds) -> dict[str, list[Run]]:
    """``scene`` planned per seed before and after (alternating which runs first); runs per side."""
    from lazyground import api
    from lazyground.drake.world import DrakeWorld

    world = DrakeWorld(scene, visual=False)
    sides = {"before": (without_angled(scene), {"goal_learning": 0.0}), "after": (scene, {})}
    runs = {side: [] for side in sides}
    api.plan(scene, request, seed=0, world=world)  # warm-up: the world's one-time builds (reach map, hand probe)
    for seed in seeds:
        for side in (("before", "after") if seed % 2 == 0 else ("after", "before")):
            s, overrides = sides[side]
            report = api.plan(s, request, seed=seed, world=world, **overrides)
            res = report.result
            runs[side].append(Run(name, seed, res.status.value, report.time_s, 0.0, report.chosen_object, res.iterations))
    return runs


def ab_entries(only, out_dir: Path):
    """(name, scene, request) of the corpus and the bundled Fetch scenes."""
    from lazyground.bundled import bundled_scene
    from lazyground.scene import load_scene

    for entry in corpus_entries():
        if not only or entry.name in only:
            yield entry.name, load_scene(import_entry(entry, out_dir).output), entry.request
    for name, request in BUNDLED_FETCH.items():
        if not only or name in only:
            yield name, load_scene(bundled_scene(name)), request


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 per scene")
    parser.add_argument("--only", action="append", help="scene names (repeatable; default: all)")
    parser.add_argument("--ab", action="store_true", help="before / after issue 34's grasps and goal learning, in one run")
    args = parser.parse_args(argv)
    runs = []
    rows = ["| scene | before solved | after solved | before median s | after median s | after / before |",
            "| --- | --- | --- | --- | --- | --- |"]
    totals = {"before": [], "after": []}
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene, request in ab_entries(args.only, Path(tmp)) if args.ab else ():
            sides = ab_scene(name, scene, request, range(args.seeds))
            med = {k: statistics.median(r.time_s for r in v) for k, v in sides.items()}
            ok = {k: sum(r.status == "solved" for r in v) for k, v in sides.items()}
            for k in totals:
                totals[k] += sides[k]
            rows.append(f"| {name} | {ok['before']}/{args.seeds} | {ok['after']}/{args.seeds} | {med['before']:.2f} | "
                        f"{med['after']:.2f} | {med['after'] / med['before']:.2f} |")
            print(rows[-1], file=sys.stderr, flush=True)
        for entry in corpus_entries() if not args.ab else ():
            if args.only and entry.name not in args.only:
                continue
            mine, _ = run_entry(entry, Path(tmp), range(args.seeds))
            runs += mine
            print(f"{entry.name}: {sum(r.status == 'solved' for r in mine)}/{len(mine)} solved", file=sys.stderr, flush=True)
    if args.ab:
        med = {k: statistics.median(r.time_s for r in v) for k, v in totals.items()}
        ok = {k: sum(r.status == "solved" for r in v) for k, v in totals.items()}
        n = len(totals["after"])
        rows.append(f"| **all** | {ok['before']}/{n} | {ok['after']}/{n} | {med['before']:.2f} | {med['after']:.2f} | "
                    f"{med['after'] / med['before']:.2f} |")
        print("\n".join(rows))
        return 0
    print("\n".join(table(runs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
