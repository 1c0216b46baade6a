"""Issue #33: the approach-clearance flag (lazyground.drake.approach) on an arm rack: the window cans' grasps cannot
back out along the approach axis (the pane's window admits the palm only lengthwise), the reachable can's can."""

import numpy as np
import pytest
from pydrake.geometry import Box, Cylinder

from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.bench.runner import load_problem
from lazyground.drake.approach import POSES, STEP, blocked_approaches, hand, surface_points
from lazyground.geometry import rpy_to_matrix
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


def _blocked_alone(world, region, rng) -> bool:
    """The flag as it was computed before the batch (#33): one region at a time, every pose and step in numpy against
    the solids within 5 cm of the pose's retreat (no compiled code)."""
    a = np.asarray(getattr(region, "approach", (0.0, 0.0, 0.0)), float)
    if region.kind != "workspace" or not np.any(a) or not world.plant.HasFrameNamed(region.frame):
        return False
    h = hand(world, region.frame)
    keep = np.array(list(h.names), dtype=object)[h.owners] != region.object
    if not len(h.points) or not keep.any():
        return False
    d = a / np.linalg.norm(a)
    along = h.points @ d
    steps = np.arange(int(np.ceil(float(along.max() - along.min()) / STEP)) + 1) * STEP
    lower, span, _ = region.unit_map()
    X_WR, X_SE = region.X_WR.matrix(), region.X_SE.matrix()
    vs = np.vstack([lower + span / 2, lower + span * rng.random((POSES, len(span)))])
    R = np.stack([X_WR[:3, :3] @ rpy_to_matrix(v[3:6]) @ X_SE[:3, :3] for v in vs])
    t = (X_WR[:3, :3] @ vs[:, :3].T).T + X_WR[:3, 3] + R @ X_SE[:3, 3]
    p = np.einsum("kij,mj->kmi", R, h.points) + t[:, None, :]
    (centres, axes, half, rounding), reach = (s[keep] for s in h.solids), h.reach[keep]
    for k in range(len(p)):
        x = (p[k][None] + steps[:, None, None] * (R[k] @ d)).reshape(-1, 3)
        near = np.all(np.abs(np.clip(centres, x.min(axis=0) - 0.05, x.max(axis=0) + 0.05) - centres) <= reach + h.tol, axis=1)
        local = np.einsum("psj,sji->psi", x[:, None, :] - centres[near][None], axes[near])
        e = np.abs(local) - half[near][None]
        dist = np.sqrt(np.sum(np.maximum(e, 0.0) ** 2, axis=2)) + np.minimum(e.max(axis=2), 0.0) - rounding[near][None]
        if not np.any(dist < h.tol):
            return False
    return True


@pytest.mark.parametrize("key", ["rack:panda:4:1:0", "rack:panda:16:1:1", "rack:fetch:4:1:1", "rack:fetch:16:1:0",
                                 "yaml_scenes/fetch_boxes_3.yaml", "yaml_scenes/panda_tabletop.yaml"])
def test_all_regions_at_once_flag_what_one_region_at_a_time_flags(key):
    """blocked_approaches (every region's poses in one compiled call, solids pre-tested by boxes, #33) flags what the
    plain test of one region at a time flags, with the same seeded poses."""
    problem = load_problem(key)
    regions, _ = problem.ground()
    drops = reach_prior_drops(regions, problem.world)
    flagged = blocked_approaches(problem.world, tuple(regions), drops, np.random.default_rng(0))
    rng = np.random.default_rng(0)
    alone = {j for j, r in enumerate(regions) if j not in drops and _blocked_alone(problem.world, r, rng)}
    assert flagged == alone
    assert flagged and len(flagged) < len(regions) - len(drops) or key.startswith("yaml_scenes/")
