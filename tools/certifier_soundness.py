"""The compiled sphere certifier against Drake's checker on every bundled arm scene (#31).

    python3 tools/certifier_soundness.py                 # 20k configurations, 2k edges, 40 sweeps per scene
    python3 tools/certifier_soundness.py --configs 2000 --edges 200 --sweeps 10 --scenes fetch_cans_1

Configurations: uniform samples, near-contact ones (bisections between a free and a colliding
sample down to ~1e-5 rad) and the rows of random straight edges. Per configuration the
certifier's code (proven free / open / proven colliding) is compared with Drake's
``CheckConfigCollisionFree``; per edge (random ends, at the scene's edge resolution) the
checker's ``edge_free`` and ``edge_fraction`` with Drake's ``CheckEdgeCollisionFree`` and
``MeasureEdgeCollisionFree`` on a checker built without certifier; per sweep (a random straight
segment stepped every 0.005, all in one sequence) the rows the sequence test (``sweep``) calls
free or colliding against Drake's answers; per configuration (a quarter as many) the penetration test
``config_unpadded_free`` asks the kernel (thresholds less the padding) against SceneGraph's penetration
query. Prints one line per scene and
exits 1 on any mismatch where the certifier claims an answer.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from lazyground.drake.certify_check import compare_configs, compare_edges, compare_penetration, compare_sweeps  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--configs", type=int, default=20000, help="configurations per scene")
    ap.add_argument("--edges", type=int, default=2000, help="edges per scene")
    ap.add_argument("--sweeps", type=int, default=40, help="finely stepped random segments per scene")
    ap.add_argument("--scenes", default="", help="comma-separated scene names (default: every bundled arm scene)")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    names = args.scenes.split(",") if args.scenes else sorted(
        p.stem for p in (ROOT / "yaml_scenes").glob("*.yaml") if not p.stem.startswith("parking"))
    bad, totals = 0, np.zeros(9, int)
    for name in names:
        t0 = time.perf_counter()
        world = DrakeWorld(load_scene(str(ROOT / "yaml_scenes" / f"{name}.yaml")), visual=False)
        rng = np.random.default_rng(args.seed)
        c = compare_configs(world, rng, args.configs)
        e = compare_edges(world, rng, args.edges)
        s = compare_sweeps(world, rng, args.sweeps)
        u = compare_penetration(world, rng, args.configs // 4)
        bad += c.wrong_free + c.wrong_collides + e.mismatches + s.wrong_free + s.wrong_collides
        bad += u.wrong_free + u.wrong_collides if u is not None else 0
        totals += [c.configs, c.proven_free, c.proven_colliding, c.wrong_free + c.wrong_collides, e.edges, e.mismatches,
                   s.configs, s.proven_free, s.wrong_free + s.wrong_collides]
        print(f"{name}: {c.configs} configurations (Drake free {c.drake_free}): proven free {c.proven_free}, "
              f"proven colliding {c.proven_colliding}, open {c.open}; wrong: free {c.wrong_free}, colliding "
              f"{c.wrong_collides}; {e.edges} edges ({e.free} free): mismatches {e.mismatches}; sweeps: {s.configs} "
              f"rows (Drake free {s.drake_free}): proven free {s.proven_free}, wrong {s.wrong_free + s.wrong_collides} "
              f"{_penetration(u)} [{time.perf_counter() - t0:.0f} s]", flush=True)
    print(f"total: {totals[0]} configurations ({totals[1]} proven free, {totals[2]} proven colliding), "
          f"{totals[3]} wrong; {totals[4]} edges, {totals[5]} mismatches; {totals[6]} sweep rows ({totals[7]} proven "
          f"free), {totals[8]} wrong")
    return 1 if bad else 0


def _penetration(u) -> str:
    if u is None:
        return "; penetration: not asked"
    return (f"; penetration (config_unpadded_free): {u.configs} rows (none penetrating {u.drake_free}): proven "
            f"none {u.proven_free}, proven some {u.proven_colliding}, wrong {u.wrong_free + u.wrong_collides}")


if __name__ == "__main__":
    sys.exit(main())
