"""grounding.spatial on its own: footprints, supports, units of boards, thirds, rows; each expectation worked by hand.

The grounding tests reach these functions through whole requests; these pin the rules the module's docstring
states (3 cm contact, footprints in the support's own frame, boards grouped by unit name else by overlapping
footprints, the thirds of the spread, rows by heading and gaps), at and just past their boundaries.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from grounding import spatial
from lazyground.scene.schema import Cylinder, Geometry, PoseSpec, SceneObject


def box(id, size, xyz, yaw=0.0, type="table", **kw):
    return SceneObject(id, type, Geometry(box=tuple(size)), PoseSpec(tuple(xyz), (0.0, 0.0, yaw)), **kw)


def cyl(id, r, length, xyz, type="can", **kw):
    return SceneObject(id, type, Geometry(cylinder=Cylinder(r, length)), PoseSpec(tuple(xyz)), **kw)


def scene(*objects):
    return SimpleNamespace(objects=list(objects))


# --- footprints -------------------------------------------------------------------------------------------


def test_a_box_footprint_is_read_in_the_support_frame():
    # a 1.0 x 0.4 board at (2, 1) turned 90 degrees: in the world it spans x 1.8..2.2, y 0.5..1.5
    board = box("b", (1.0, 0.4, 0.04), (2.0, 1.0, 0.5), yaw=math.pi / 2)
    assert spatial._over_footprint(np.array([2.15, 1.45, 0.52]), board)  # inside the turned board
    assert not spatial._over_footprint(np.array([2.45, 1.15, 0.52]), board)  # inside it were it not turned
    assert not spatial._over_footprint(np.array([2.0, 1.6, 0.52]), board)  # 0.1 m past its far end
    assert not spatial._over_footprint(np.array([2.3, 1.0, 0.52]), board)  # 0.1 m past its side


def test_a_box_footprint_includes_its_edges_and_nothing_past_them():
    board = box("b", (1.0, 0.4, 0.04), (0.0, 0.0, 0.5))
    assert spatial._over_footprint(np.array([0.5, 0.0, 0.5]), board)  # on the x edge
    assert spatial._over_footprint(np.array([0.0, -0.2, 0.5]), board)  # on the y edge
    assert spatial._over_footprint(np.array([0.5, 0.2, 0.5]), board)  # the corner
    assert not spatial._over_footprint(np.array([0.501, 0.0, 0.5]), board)
    assert not spatial._over_footprint(np.array([0.0, 0.201, 0.5]), board)
    assert not spatial._over_footprint(np.array([1.2, 0.0, 0.5]), board)  # 0.7 m past the edge
    assert not spatial._over_footprint(np.array([0.0, 0.9, 0.5]), board)


def test_a_round_footprint_is_a_disc_in_the_ground_plane():
    table = cyl("t", 0.4, 0.05, (1.0, -1.0, 0.7), type="table")
    # (0.1, 0.35) from the centre: 0.364 m < 0.4; its height above the table's centre plays no part
    assert spatial._over_footprint(np.array([1.1, -0.65, 1.5]), table)
    assert spatial._over_footprint(np.array([1.35, -0.9, 0.7]), table)
    # (0.3, 0.3): each coordinate within 0.4 but 0.424 m from the centre: off the disc
    assert not spatial._over_footprint(np.array([1.3, -0.7, 0.725]), table)
    assert spatial._over_footprint(np.array([0.6, -1.0, 0.725]), table)  # on the rim: over it
    assert not spatial._over_footprint(np.array([1.0, -0.5, 0.725]), table)  # 0.5 m out along y
    assert not spatial._over_footprint(np.array([1.9, -1.0, 0.725]), table)  # 0.9 m out along x


# --- support ----------------------------------------------------------------------------------------------


def test_support_is_the_face_under_the_object_within_3_cm():
    table = box("table", (1.0, 1.0, 0.04), (0.0, 0.0, 0.68))  # top at 0.70
    on = cyl("on", 0.03, 0.1, (0.2, 0.2, 0.75))  # bottom 0.70
    above = cyl("above", 0.03, 0.1, (-0.2, 0.2, 0.77))  # bottom 0.72: 2 cm up, still on it
    floating = cyl("floating", 0.03, 0.1, (0.2, -0.2, 0.80))  # bottom 0.75: 5 cm up, on nothing
    beside = cyl("beside", 0.03, 0.1, (0.7, 0.0, 0.75))  # at the table's height, off its footprint
    s = scene(table, on, above, floating, beside)
    assert spatial.support_of(on, s) == "table"
    assert spatial.support_of(above, s) == "table"
    assert spatial.support_of(floating, s) is None
    assert spatial.support_of(beside, s) is None


def test_the_floor_tolerance_is_inclusive():
    table = box("table", (1.0, 1.0, 0.04), (0.0, 0.0, 0.68))
    low = cyl("low", 0.03, 0.1, (3.0, 3.0, 0.08))  # bottom exactly 3 cm above the floor
    assert spatial.world_box(low)[0][2] == spatial.TOUCH_TOL
    assert spatial.support_of(low, scene(table, low)) == spatial.FLOOR
    higher = cyl("higher", 0.03, 0.1, (3.0, 3.0, 0.0801))
    assert spatial.support_of(higher, scene(table, higher)) is None


def test_the_closest_face_wins_and_a_low_tray_beats_the_floor():
    tray = box("tray", (0.4, 0.4, 0.01), (0.0, 0.0, 0.005), type="tray")  # a 1 cm tray on the floor, top 0.01
    can = cyl("can", 0.03, 0.1, (0.0, 0.0, 0.06))  # bottom 0.01: on the tray, 1 cm above the floor
    assert spatial.support_of(can, scene(tray, can)) == "tray"
    shelf = box("shelf", (0.6, 0.6, 0.02), (0.0, 0.0, 0.69))  # top 0.70
    board = box("board", (0.6, 0.6, 0.02), (0.0, 0.0, 0.705))  # a board laid on it, top 0.715
    cup = cyl("cup", 0.03, 0.1, (0.0, 0.0, 0.766))  # bottom 0.716: 1 mm over the board, 1.6 cm over the shelf
    assert spatial.support_of(cup, scene(shelf, board, cup)) == "board"
    assert spatial.support_of(cup, scene(board, shelf, cup)) == "board"


def test_an_object_is_not_its_own_support_nor_is_what_does_not_collide():
    plate = box("plate", (0.2, 0.2, 0.02), (0.0, 0.0, 1.0), type="tray")  # floating, 2 cm thick
    assert spatial.support_of(plate, scene(plate)) is None
    spot = box("spot", (2.0, 4.0, 0.01), (0.0, 0.0, 0.3), type="parking_spot")  # does not collide
    can = cyl("can", 0.03, 0.1, (0.0, 0.0, 0.36))  # bottom 0.31, right on the spot's top
    assert not spot.collides
    assert spatial.support_of(can, scene(spot, can)) is None
    solid_spot = box("spot", (2.0, 4.0, 0.01), (0.0, 0.0, 0.3), type="parking_spot", collision=True)
    assert spatial.support_of(can, scene(solid_spot, can)) == "spot"


# --- units of boards --------------------------------------------------------------------------------------


def ids(groups):
    return sorted(sorted(o.id for o in g) for g in groups)


def test_boards_sharing_a_unit_name_are_one_unit_wherever_they_stand():
    a = box("a", (0.4, 0.4, 0.02), (0.0, 0.0, 0.4), type="shelf", attributes={"unit": "rack"})
    b = box("b", (0.4, 0.4, 0.02), (2.0, 0.0, 0.8), type="shelf", attributes={"unit": "rack"})  # 1.6 m away
    c = box("c", (0.4, 0.4, 0.02), (0.0, 0.0, 0.8), type="shelf", attributes={"unit": "other"})  # over a
    assert ids(spatial.units([a, b, c])) == [["a", "b"], ["c"]]


def test_unnamed_boards_are_one_unit_where_their_footprints_overlap():
    low = box("low", (0.4, 0.8, 0.02), (0.0, 0.0, 0.4), type="shelf")
    top = box("top", (0.4, 0.8, 0.02), (0.05, 0.0, 0.8), type="shelf")  # stacked, 5 cm off
    far = box("far", (0.4, 0.8, 0.02), (3.0, 0.0, 0.4), type="shelf")
    assert ids(spatial.units([low, top, far])) == [["far"], ["low", "top"]]


@pytest.mark.parametrize("order", [1, -1])
def test_boards_side_by_side_or_touching_are_separate_units(order):
    """Neighbours along x, overlapping in y: each lies wholly to one side of the other (touching or 0.5 m
    apart). Both orders, since the newer board is compared with the earlier ones."""
    left = box("left", (0.4, 0.8, 0.02), (0.0, 0.0, 0.4), type="shelf")
    touching = box("touching", (0.4, 0.8, 0.02), (0.4, 0.0, 0.4), type="shelf")  # edge to edge at x = 0.2
    apart = box("apart", (0.4, 0.8, 0.02), (0.0, 1.3, 0.4), type="shelf")  # beside along y
    for other in (touching, apart):
        assert ids(spatial.units([left, other][::order])) == sorted([[left.id], [other.id]])
    # an overlap of 1 cm joins them (more than the 1 mm the test allows)
    lapped = box("lapped", (0.4, 0.8, 0.02), (0.39, 0.0, 0.8), type="shelf")
    assert ids(spatial.units([left, lapped][::order])) == [["lapped", "left"]]


# --- thirds and extremes ----------------------------------------------------------------------------------


def test_thirds_split_the_range_of_values_not_the_count():
    # range 0.9 from 0.1 to 1.0: high >= 0.7, low <= 0.4
    values = {"a": 1.0, "b": 0.95, "c": 0.7, "d": 0.69, "e": 0.41, "f": 0.4, "g": 0.1}
    assert spatial.thirds(values, 0.05) == {"a": "high", "b": "high", "c": "high", "d": "mid", "e": "mid",
                                            "f": "low", "g": "low"}
    assert spatial.thirds({"a": 0.25, "b": 0.3}, 0.0625) is None  # 5 cm apart, spread 6.25 cm: too close to tell
    assert spatial.thirds({"a": 0.25, "b": 0.3125}, 0.0625) == {"a": "low", "b": "high"}  # the spread itself: told
    assert spatial.thirds({}, 0.05) == {}


def test_extremes_keep_every_value_within_tol_of_the_best():
    values = {"a": 1.0, "b": 0.98, "c": 0.97, "d": 0.1}
    assert spatial.extremes(values, True, 0.025) == {"a", "b"}
    assert spatial.extremes(values, False, 0.025) == {"d"}
    assert spatial.extremes(values, False, 0.9) == {"d", "c", "b", "a"}
    assert spatial.extremes({}, True, 0.1) == set()


# --- the robot's frame and distances ----------------------------------------------------------------------


def robot(base=None, start=None):
    return SimpleNamespace(robot=SimpleNamespace(base=base, start=start or {}))


def test_the_robot_pose_comes_from_its_base_else_its_start_joints():
    based = robot(base=PoseSpec((2.0, 1.0, 0.3), (0.0, 0.0, 0.5)), start={"car_x": 9.0, "car_qz": 1.0})
    assert spatial.robot_yaw(based) == 0.5
    assert np.array_equal(spatial.robot_position(based), [2.0, 1.0, 0.3])
    car = robot(start={"car_x": 3.0, "car_y": -4.0, "car_qz": 1.25})
    assert spatial.robot_yaw(car) == 1.25
    assert np.array_equal(spatial.robot_position(car), [3.0, -4.0, 0.0])
    for key in ("theta", "yaw", "base_theta", "base_yaw"):
        assert spatial.robot_yaw(robot(start={key: -0.7, "x": 1.0})) == -0.7
    bare = robot(start={"x": 1.5, "joint_1": 0.3})
    assert spatial.robot_yaw(bare) == 0.0
    assert np.array_equal(spatial.robot_position(bare), [1.5, 0.0, 0.0])
    assert np.array_equal(spatial.robot_position(robot(start={"y": 2.5})), [0.0, 2.5, 0.0])


def test_robot_frame_is_ahead_and_left_of_the_base():
    # base at (1, 2) facing world +y (yaw pi/2): ahead is +y, left is -x
    s = robot(start={"x": 1.0, "y": 2.0, "yaw": math.pi / 2})
    ahead, left = spatial.robot_frame((1.5, 5.0), s)
    assert ahead == pytest.approx(3.0) and left == pytest.approx(-0.5)
    ahead, left = spatial.robot_frame((0.0, 2.0), s)
    assert ahead == pytest.approx(0.0, abs=1e-12) and left == pytest.approx(1.0)


def test_distance_to_point_is_to_the_bounds_in_the_ground_plane():
    b = box("b", (1.0, 0.4, 2.0), (0.0, 0.0, 1.0))  # x -0.5..0.5, y -0.2..0.2
    assert spatial.distance_to_point(b, np.array([0.1, 0.1, 5.0])) == 0.0  # over it: 0, whatever the height
    assert spatial.distance_to_point(b, np.array([1.5, 0.0, 0.0])) == pytest.approx(1.0)
    assert spatial.distance_to_point(b, np.array([0.0, -0.5, 9.0])) == pytest.approx(0.3)
    assert spatial.distance_to_point(b, np.array([0.8, 0.6, 0.0])) == pytest.approx(0.5)  # a 0.3-0.4-0.5 corner
    c = cyl("c", 0.05, 0.1, (3.5, 0.0, 0.05))
    assert spatial.distance_between(c, b) == pytest.approx(3.0)


# --- rows -------------------------------------------------------------------------------------------------


def spot(id, x, y, yaw=0.0):
    return box(id, (2.5, 5.0, 0.01), (x, y, 0.0), yaw=yaw, type="parking_spot")


def test_rows_are_lines_of_one_heading_split_at_wide_gaps():
    # spots facing +x (yaw 0) side by side along y every 2.5 m, a 5 m gap after the third; a second line
    # 6 m further along x; two spots turned 90 degrees (their own row, ordered across it by -x); one at yaw pi
    # 0.2 m off the first line (the same line: heading mod 180 degrees, within 0.5 m), ordered by y
    line = [spot(f"a{i}", 0.0, 2.5 * i) for i in range(3)] + [spot("a3", 0.0, 10.0), spot("a4", 0.0, 12.5)]
    second = [spot("b0", 6.0, 0.0), spot("b1", 6.0, 2.5)]
    turned = [spot("t0", 20.0, 0.0, yaw=math.pi / 2), spot("t1", 22.5, 0.0, yaw=math.pi / 2)]
    back = [spot("r0", 0.2, -2.5, yaw=math.pi)]
    off = [spot("s0", -0.5, 15.0)]  # 0.5 m off the first line: not within it (tol 0.5 is exclusive)
    out = spatial.rows(line + second + turned + back + off)
    assert sorted([o.id for o in r] for r in out) == [["a3", "a4"], ["b0", "b1"], ["r0", "a0", "a1", "a2"], ["s0"],
                                                      ["t1", "t0"]]
