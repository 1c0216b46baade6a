"""Issue 34: the car stays inside its lot along every curve, shortcut and trajectory sample, not only at nodes.

On the tutorial's lot (limits, no perimeter walls) seed 4 returned a path with car_y up to 20.67 of 20, and
walls around a spot that end at the lot's edge were driven around outside it. Bounded by iterations.
"""

import re
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.scene import parse_scene  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LOT = re.findall(r"```yaml\n(.*?)```", (ROOT / "docs/tutorial.md").read_text(), re.S)[0]
# a spot at the lot's top edge, walled on three sides up to the edge: entering it from outside the lot is not allowed
WALLED = LOT.replace("objects:\n", """objects:
  - {id: spot_b1, type: parking_spot, geometry: {box: [5.5, 2.6, 0.05]}, pose: {xyz: [8, 17, 0.025], rpy: [0, 0, 1.5708]}}
""").replace("obstacles:\n", """obstacles:
  - {id: wall_l, geometry: {box: [0.2, 7, 2]}, pose: {xyz: [6.3, 16.5, 1]}}
  - {id: wall_r, geometry: {box: [0.2, 7, 2]}, pose: {xyz: [9.7, 16.5, 1]}}
  - {id: wall_b, geometry: {box: [3.6, 0.2, 2]}, pose: {xyz: [8, 13, 1]}}
""")
TOL = 1e-6  # m


def _inside(report, limits) -> list[str]:
    names = list(report.joint_names)
    out = []
    arrays = {"path": report.result.path}
    if report.motion is not None:
        arrays["raw path"] = report.motion.raw_path
        if report.motion.trajectory is not None:
            arrays["trajectory"] = report.motion.trajectory.q
    for what, q in arrays.items():
        for name, (lo, hi) in limits.items():
            v = np.asarray(q)[:, names.index(name)]
            if v.min() < lo - TOL or v.max() > hi + TOL:
                out.append(f"{what} {name} in [{v.min():.2f}, {v.max():.2f}], limits [{lo}, {hi}]")
    return out


# the walled spot opens only onto the lot's edge: no seed may reach it (it did by driving outside the lot); the
# test asserted "at least 0 solved" before, which no outcome could fail (0 of 10 seeds solve, 2026-11-26)
@pytest.mark.parametrize("text,request_,solved_at_least,solved_at_most", [(LOT, "park", 10, 10), (WALLED, "park in spot_b1", 0, 0)],
                         ids=["tutorial_lot", "walled_spot_at_the_edge"])
def test_the_car_stays_inside_its_lot(text, request_, solved_at_least, solved_at_most):
    scene = parse_scene(text, "lot.yaml", ROOT)
    solved, outside = 0, []
    for seed in range(10):
        report = api.plan(scene, request_, seed=seed, kinematics="reeds-shepp", time_limit=1e6,
                          max_iterations=20_000 if solved_at_least else 1_500)
        if report.result.solved:
            solved += 1
            outside += [f"seed {seed}: {p}" for p in _inside(report, scene.robot.limits)]
    assert outside == []
    assert solved_at_least <= solved <= solved_at_most
