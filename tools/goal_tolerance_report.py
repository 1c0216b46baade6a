"""How far IK goal configurations land outside their regions, at three IK tolerances (docs/fetch.md).

Usage: PYTHONPATH=. python3 tools/goal_tolerance_report.py [SAMPLES_PER_SETTING]
"""
import sys
import time

import numpy as np
import grounding
from lazyground.drake.ik import IKGoalSource, IKSettings, region_coordinates
from lazyground.drake.world import DrakeWorld
from lazyground.geometry import wrap_angle
from lazyground.planning.stop import StopCondition
from lazyground.scene import load_scene

def excess(region, v):
    pos, ang = [], []
    for i, (x, lo, hi) in enumerate(zip(v, region.lower, region.upper)):
        if i in region.wrap and hi - lo >= 2 * np.pi - 1e-9:
            e = 0.0
        elif i in region.wrap:
            mid = lo + (hi - lo) / 2; e = max(0.0, abs(wrap_angle(x - mid)) - (hi - lo) / 2)
        else:
            e = max(lo - x, x - hi, 0.0)
        (pos if i < 3 else ang).append(e)
    return float(np.linalg.norm(pos)), float(max(ang))

for name, req in (("fetch_cans_1", "pick up a can"), ("fetch_boxes_3", "pick up a box")):
    scene = load_scene(name); world = DrakeWorld(scene)
    regions = grounding.ground(req, scene).goal_regions
    for pt, ot in ((0.002, 0.01), (0.0005, 0.0025), (0.0002, 0.001)):
        s = IKSettings(position_tolerance=pt, orientation_tolerance=ot)
        src = IKGoalSource(regions, world, s)
        t0 = time.perf_counter()
        samples = src.draw(int(sys.argv[1]) if len(sys.argv) > 1 else 30, np.random.default_rng(0), StopCondition.after(120))
        dt = time.perf_counter() - t0
        ex = [excess(src.regions[x.region], region_coordinates(src.regions[x.region], src.frame_pose(src.regions[x.region].frame, world.full(x.end)))) for x in samples]
        c = src.counters
        attempts = sum(st.attempts for st in src.stats)
        print(f"{name} tol ({pt*1e3:.1f} mm, {ot:.4f} rad): {len(samples)} samples in {attempts} attempts, {dt:.1f} s; "
              f"IK {c.successes}/{c.solves} ok, {1e3*c.time/max(c.solves,1):.1f} ms/solve; "
              f"outside region: max {1e3*max(e[0] for e in ex):.2f} mm, {max(e[1] for e in ex):.4f} rad; "
              f"inside (1e-6): {sum(e[0] <= 1e-6 and e[1] <= 1e-6 for e in ex)}/{len(ex)}", flush=True)
