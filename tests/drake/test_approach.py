"""Issue #33: the approach-clearance flag (lazyground.drake.approach) on an arm rack: the window cans' grasps cannot
back out along the approach axis (the pane's window admits the palm only lengthwise), the reachable can's can."""

import numpy as np
import pytest
from pydrake.geometry import Box, Cylinder

from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.bench.runner import load_problem
from lazyground.drake.approach import blocked_approaches, surface_points
from lazyground.goals import reach_prior_drops


@pytest.mark.parametrize("robot,layout", [("panda", 0), ("fetch", 0)])
def test_window_grasps_are_flagged_and_a_reachable_grasp_is_not(robot, layout):
    key = f"rack:{robot}:4:1:{layout}"
    kinds = can_kinds(generate(parse_key(key)))
    problem = load_problem(key)
    regions, _ = problem.ground()
    drops = reach_prior_drops(regions, problem.world)
    flagged = blocked_approaches(problem.world, tuple(regions), drops, np.random.default_rng(0))
    kept = [j for j in range(len(regions)) if j not in drops]
    kind = {j: kinds[regions[j].object] for j in kept}
    assert all(j in flagged for j in kept if kind[j] == "window")
    assert any(j not in flagged for j in kept if kind[j] == "reachable")
    assert not flagged & set(drops)  # dropped regions are not tested
    assert blocked_approaches(problem.world, tuple(regions), drops) is blocked_approaches(problem.world, tuple(regions), drops)


def test_surface_points_lie_on_the_shapes():
    p = surface_points(Box(0.1, 0.2, 0.3), 0.02)
    assert np.allclose(np.max(np.abs(p) - [0.05, 0.1, 0.15], axis=1), 0.0)
    c = surface_points(Cylinder(0.05, 0.2), 0.02)
    r = np.hypot(c[:, 0], c[:, 1])
    assert np.all((np.isclose(r, 0.05) & (np.abs(c[:, 2]) <= 0.1 + 1e-12)) | np.isclose(np.abs(c[:, 2]), 0.1))
