"""The reach prior's grid (lazyground/planning/reach_prior.py, issue #33): sound on constructed geometry.

Sound: a blocked cell holds no point whose ball (radius r) stays clear of the obstacles, and a goal box is
dropped only if no ball path joins it to the start. Checked on a gap exactly at the limit, a rotated box, a
disc (a cylinder seen from above) and a ball in 3D, against the exact distances."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lazyground.geometry import rpy_to_matrix
from lazyground.planning.reach_prior import TOLERANCE, PlanarReach, Solid, _arc_box, pose_centre_box, reach_grid
from lazyground.regions import ConfigRegion

R = 0.9  # a car's disc


def _room_with_gap(gap: float, cell: float):
    """A 20 x 10 m box split at x = 10 by a wall with a gap of ``gap`` m in the middle (y = 5)."""
    wall = 0.2
    lower = (5 - gap / 2) / 2
    solids = [Solid((10.0, lower), (wall / 2, lower)),  # from y = 0 up to the gap
              Solid((10.0, 10 - lower), (wall / 2, lower))]  # from the gap up to y = 10
    outer = [Solid((10.0, -0.5), (10.5, 0.5)), Solid((10.0, 10.5), (10.5, 0.5)),
             Solid((-0.5, 5.0), (0.5, 5.5)), Solid((20.5, 5.0), (0.5, 5.5))]
    return reach_grid((0.0, 0.0), (20.0, 10.0), R, solids + outer, cell)


def _region(x, y, tol=0.3):
    return ConfigRegion("g", "park:g", "g", (x - tol, y - tol, -0.1), (x + tol, y + tol, 0.1), wrap=(2,))


def _prior(grid, start_xy, offset=(0.0, 0.0)):
    c = np.asarray(start_xy, float)
    return PlanarReach(grid, frozenset(grid.components(c - 1e-9, c + 1e-9)), (0, 1, 2), offset)


@pytest.mark.parametrize("cell", [0.05, 0.1125, 0.2])
def test_a_gap_exactly_as_wide_as_the_disc_keeps_the_far_side(cell):
    """A disc of radius r fits through a gap of 2r touching both sides: the prior must keep the far side at every
    cell size (sound); a gap 0.2 m too narrow is closed at the cell sizes that resolve it."""
    grid = _room_with_gap(2 * R, cell)
    prior = _prior(grid, (3.0, 5.0))
    assert prior.keeps(_region(17.0, 5.0))
    narrow = _prior(_room_with_gap(2 * R - 0.2, cell), (3.0, 5.0))
    assert narrow.keeps(_region(3.0, 8.0))  # the start's side
    if cell * math.sqrt(2) / 2 < 0.1:  # closed when the cells resolve its 0.1 m of slack (coarser ones may, by luck)
        assert not narrow.keeps(_region(17.0, 5.0))


def test_a_wall_without_gap_drops_the_far_side_and_a_box_straddling_it_is_kept():
    grid = _room_with_gap(0.0, 0.1)
    prior = _prior(grid, (3.0, 5.0))
    assert not prior.keeps(_region(17.0, 5.0))
    assert prior.keeps(ConfigRegion("g", "park:g", "g", (5.0, 4.0, 0.0), (15.0, 6.0, 0.1)))  # one cell on the start's side


def _blocked_is_sound(grid, solids, rng, lower, upper, n=40_000):
    """Every sampled point in a blocked cell has its ball (radius grid.radius) reaching into a solid."""
    p = rng.uniform(lower, upper, (n, len(lower)))
    blocked = grid.blocked(p)
    d = np.min([s.distance(p) for s in solids], axis=0)
    assert not np.any(blocked & (d >= grid.radius)), "a blocked cell holds a point whose ball is clear"
    return blocked, d


@pytest.mark.parametrize("angle", [0.0, 0.3, math.pi / 6, 1.1, math.pi / 2])
def test_a_rotated_box_blocks_only_cells_whose_every_disc_hits_it(angle):
    c, s = math.cos(angle), math.sin(angle)
    box = Solid((5.0, 5.0), (3.0, 0.15), 0.0, ((c, -s), (s, c)))
    grid = reach_grid((0.0, 0.0), (10.0, 10.0), R, [box], 0.1)
    blocked, d = _blocked_is_sound(grid, [box], np.random.default_rng(0), (0, 0), (10, 10))
    assert blocked[d < R - 0.1 * math.sqrt(2) - 1e-3].all()  # and tight: a point its cell's diagonal within is blocked
    assert blocked.any() and not blocked.all()


def test_a_cylinder_seen_from_above_is_a_disc():
    post = Solid((5.0, 5.0), (0.0, 0.0), 0.4)  # a cylinder of radius 0.4 m
    grid = reach_grid((0.0, 0.0), (10.0, 10.0), R, [post], 0.1)
    blocked, d = _blocked_is_sound(grid, [post], np.random.default_rng(1), (0, 0), (10, 10))
    assert blocked[d < R - 0.1 * math.sqrt(2) - 1e-3].all()
    assert np.allclose(post.distance(np.array([[5.0, 7.0]])), 1.6)


def test_in_three_dimensions_a_ball_among_balls_and_boxes():
    """n-D: a 3D grid of a hand's ball (radius 0.1) among a ball and a rotated box."""
    c, s = math.cos(0.4), math.sin(0.4)
    solids = [Solid((0.5, 0.5, 0.5), (0.0, 0.0, 0.0), 0.2),
              Solid((0.2, 0.7, 0.3), (0.1, 0.05, 0.2), 0.0, ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0)))]
    grid = reach_grid((0.0, 0.0, 0.0), (1.0, 1.0, 1.0), 0.1, solids, 0.02)
    blocked, d = _blocked_is_sound(grid, solids, np.random.default_rng(2), (0, 0, 0), (1, 1, 1), n=20_000)
    assert blocked[d < 0.1 - 0.02 * math.sqrt(3) - 1e-3].all()


def test_a_closed_room_is_its_own_component_and_the_ring_joins_the_outside():
    walls = [Solid((5.0, 3.0), (2.0, 0.1)), Solid((5.0, 7.0), (2.0, 0.1)),
             Solid((3.0, 5.0), (0.1, 2.1)), Solid((7.0, 5.0), (0.1, 2.1))]
    grid = reach_grid((0.0, 0.0), (10.0, 10.0), 0.5, walls, 0.1)
    inside, outside = grid.components((5, 5), (5, 5)), grid.components((1, 1), (1, 1))
    assert inside and outside and not inside & outside
    assert grid.components((-50, -50), (-49, -49)) == outside  # beyond the bounds: the free ring
    assert grid.components((9.95, 9.95), (11, 11)) == outside


def test_an_unreachable_start_keeps_everything():
    grid = reach_grid((0.0, 0.0), (10.0, 10.0), R, [Solid((5.0, 5.0), (1.0, 1.0))], 0.1)
    prior = PlanarReach(grid, frozenset(), (0, 1, 2))  # the start's disc in no free cell: the prior says nothing
    assert prior.keeps(_region(5.0, 5.0))


@pytest.mark.parametrize("seed", range(20))
def test_the_arc_box_holds_the_offset_at_every_heading_of_the_arc(seed):
    rng = np.random.default_rng(seed)
    offset = rng.normal(size=2)
    lo, span = rng.uniform(-math.pi, math.pi), rng.uniform(0, 2.5 * math.pi)
    box_lo, box_hi = _arc_box(offset, lo, span)
    t = lo + np.linspace(0, span, 400)
    pts = np.column_stack([np.cos(t) * offset[0] - np.sin(t) * offset[1], np.sin(t) * offset[0] + np.cos(t) * offset[1]])
    assert np.all(pts >= box_lo - 1e-12) and np.all(pts <= box_hi + 1e-12)
    assert np.allclose(pts.min(axis=0), box_lo, atol=1e-3) and np.allclose(pts.max(axis=0), box_hi, atol=1e-3)


def test_an_offset_disc_keeps_a_region_whose_turned_disc_reaches_the_start_side():
    """A disc 1.5 m ahead of the body frame: a body pose just past the wall is kept when its heading puts the disc
    back on the start's side, dropped when every heading of the region puts it beyond."""
    grid = _room_with_gap(0.0, 0.1)
    start = (3.0, 5.0)
    prior = _prior(grid, (start[0] + 1.5, start[1]), offset=(1.5, 0.0))
    facing_back = ConfigRegion("g", "park:g", "g", (10.2, 4.9, math.pi - 0.1), (10.3, 5.1, -math.pi + 0.1), wrap=(2,))
    facing_on = ConfigRegion("g", "park:g", "g", (10.2, 4.9, -0.1), (10.3, 5.1, 0.1), wrap=(2,))
    assert prior.keeps(facing_back) and not prior.keeps(facing_on)
    assert np.allclose(prior.centres(np.array([[1.0, 2.0, math.pi / 2]])), [[1.0, 3.5]])


def test_a_wall_from_bound_to_bound_closes_the_far_side_only_for_a_bounded_ball():
    """A wall across the whole bounds: a ball held to the bounds (a car: the planner holds every checked
    configuration to its limits) cannot pass; one that may leave them goes round through the free ring."""
    wall = [Solid((15.0, 12.0), (15.0, 0.15))]
    for bounded in (True, False):
        grid = reach_grid((0.0, 0.0), (30.0, 20.0), R, wall, 0.1, bounded=bounded)
        prior = _prior(grid, (3.0, 3.0))
        assert prior.keeps(_region(20.0, 17.0)) is not bounded
        assert prior.keeps(_region(20.0, 5.0))
    bounded = reach_grid((0.0, 0.0), (30.0, 20.0), R, [], 0.1, bounded=True)
    assert not bounded.blocked([[30.0, 20.0], [0.0, 0.0], [30.0, 0.0]]).any()  # the bounds themselves are free cells
    assert bounded.blocked([[30.2, 20.0], [-0.2, 0.0]]).all()  # beyond them: the blocked ring


def _transform(rng) -> np.ndarray:
    X = np.eye(4)
    X[:3, :3], X[:3, 3] = rpy_to_matrix(rng.uniform(-math.pi, math.pi, 3)), rng.normal(size=3)
    return X


@pytest.mark.parametrize("seed", range(20))
def test_the_box_of_centres_holds_the_point_at_every_pose_of_the_region(seed):
    """An arm's goal box (pose_centre_box): X_WR · X_RS(v) · X_ST · p for 2,000 draws v of a 6-D region (angle ranges
    up to beyond a full turn, some fixed) lie in it; a fixed orientation gives the position box moved, exactly."""
    rng = np.random.default_rng(seed)
    X_WR, X_ST, p = _transform(rng), _transform(rng), rng.normal(size=3) * 0.1
    lower = np.concatenate([rng.normal(size=3) * 0.1, rng.uniform(-4, 4, 3)])
    span = np.concatenate([rng.uniform(0, 0.1, 3), rng.uniform(0, 7, 3) * (rng.random(3) < 0.6)])
    lo, hi = pose_centre_box(X_WR, X_ST, p, lower, span)
    for v in lower + rng.random((2000, 6)) * span:
        X = np.eye(4)
        X[:3, :3], X[:3, 3] = rpy_to_matrix(v[3:]), v[:3]
        c = (X_WR @ X @ X_ST @ np.append(p, 1.0))[:3]
        assert np.all(c >= lo) and np.all(c <= hi)
    fixed = np.concatenate([span[:3], np.zeros(3)])
    lo, hi = pose_centre_box(X_WR, X_ST, p, lower, fixed)
    X = np.eye(4)
    X[:3, :3] = rpy_to_matrix(lower[3:])
    corners = [X_WR @ (X @ X_ST @ np.append(p, 1.0) + np.append(lower[:3] + fixed[:3] * np.array(b), 0.0))
               for b in np.ndindex(2, 2, 2)]
    assert np.allclose(lo, np.min(corners, axis=0)[:3], atol=1e-5) and np.allclose(hi, np.max(corners, axis=0)[:3], atol=1e-5)


def test_a_ball_within_a_reach_sphere_cannot_leave_it():
    """``reach``: the cells wholly beyond the reach are blocked, the ones it touches kept."""
    grid = reach_grid((-1.0, -1.0, -1.0), (1.0, 1.0, 1.0), 0.05, [], 0.025, bounded=True, reach=((0.0,) * 3, (0.0,) * 3, 1.0))
    start = grid.components((0, 0, 0), (0, 0, 0))
    assert start and grid.components((0.0, 0.0, 0.99), (0.0, 0.0, 0.99)) == start
    assert not grid.components((0.75, 0.75, 0.75), (0.95, 0.95, 0.95))  # |(0.75,) * 3| = 1.3: beyond the reach
    points = np.random.default_rng(0).uniform(-1, 1, (20_000, 3))
    inside = np.linalg.norm(points, axis=1) <= 1.0
    assert not np.any(grid.blocked(points) & inside)


def test_a_ball_within_reach_of_a_segment_cannot_leave_its_capsule():
    """``reach`` about a segment (a prismatic joint's travel): points within the radius of it are never blocked,
    a box wholly beyond is dropped."""
    a, b = np.array([0.1, -0.2, 0.0]), np.array([0.1, 0.3, 0.4])
    lower, upper = np.minimum(a, b) - 0.5, np.maximum(a, b) + 0.5
    grid = reach_grid(lower, upper, 0.05, [], 0.03, bounded=True, reach=(a, b, 0.5))
    points = np.random.default_rng(1).uniform(lower, upper, (20_000, 3))
    t = np.clip((points - a) @ (b - a) / ((b - a) @ (b - a)), 0, 1)
    inside = np.linalg.norm(points - a - t[:, None] * (b - a), axis=1) <= 0.5
    assert not np.any(grid.blocked(points) & inside) and grid.blocked(points[~inside]).mean() > 0.5
    assert not grid.components(upper - 0.1, upper)  # the corner: 0.5 * sqrt(3) from the segment's end


@pytest.mark.parametrize("seed", range(3))
def test_boxes_at_once_meet_the_components_one_box_at_a_time_finds(seed):
    # #33: meets (a summed-area table of the components' cells) against components (the cells' labels) box by box,
    # in 2-D (a room with a wall, gaps closed and open) and 3-D (balls among boxes), boxes inside, across and beyond
    # the grid; and a car's keeps_all against keeps
    rng = np.random.default_rng(seed)
    grids = [_room_with_gap(g, 0.25) for g in (1.0, 2.0)]
    grids.append(reach_grid((0.0, 0.0, 0.0), (4.0, 4.0, 4.0), 0.3,
                            [Solid((2.0, 2.0, 2.0), (0.4, 1.9, 0.4)), Solid((1.0, 3.0, 1.0), (0.0, 0.0, 0.0), 0.5)], 0.2))
    for grid in grids:
        n = grid.labels.ndim
        size = np.array(grid.labels.shape) * grid.cell
        lower = grid.origin + rng.uniform(-0.1, 1.0, (300, n)) * size
        upper = lower + rng.uniform(0.0, 0.3, (300, n)) * size
        labels = sorted({int(k) for k in np.unique(grid.labels) if k})
        for chosen in ({labels[0]}, set(labels), set()):
            want = [bool(grid.components(a, b) & chosen) for a, b in zip(lower, upper)]
            assert grid.meets(lower, upper, chosen).tolist() == want
    prior = _prior(grids[0], (2.0, 5.0))
    regions = [_region(x, y, tol) for x, y, tol in zip(rng.uniform(0, 20, 200), rng.uniform(0, 10, 200), rng.uniform(0.0, 2.0, 200))]
    def one(region):  # a region alone, as keeps was written before keeps_all: its disc centres' box, its components
        lower, span, _ = region.unit_map()
        lo, hi = _arc_box(np.asarray(prior.offset, float), float(lower[2]), float(span[2]))
        box = (lower[:2] + lo - TOLERANCE, lower[:2] + span[:2] + hi + TOLERANCE)
        return bool(prior.grid.components(*box) & prior.start)

    assert prior.keeps_all(regions) == [one(r) for r in regions] == [prior.keeps(r) for r in regions]
    assert 0 < sum(prior.keeps_all(regions)) < len(regions)
