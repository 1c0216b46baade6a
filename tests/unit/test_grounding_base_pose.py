"""Grounding with the robot's base turned and moved off the origin: left/right, nearest and shelves.

Every other test scene has its base at the origin with yaw 0, where the robot's frame is the world's. Here the
base stands at (2, 1) facing world +y (yaw pi/2), so the robot's left is world -x and its right world +x. The
objects are placed so that reading left/right as world y, or distances from the origin, gives a different
answer; each expectation below is worked out by hand in the comments.
"""

from __future__ import annotations

import math

import pytest

from grounding import ground, spatial
from lazyground.scene import parse_scene
from tests.unit.test_grounding import _box, _cyl, pick, place

ROBOT = """\
robot:
  model: fetch
  base: {xyz: [2.0, 1.0, 0.0], rpy: [0.0, 0.0, 1.5707963267948966]}
  end_effector: gripper_link
  start: {torso_lift_joint: 0.05}
"""
# lateral (the robot's y) of a point (x, y) = -sin(yaw) dx + cos(yaw) dy = -(x - 2) = 2 - x.
OBJECTS = [
    _box("table_1", "table", 2.0, 1.8, 0.68, 1.0, 0.8, 0.04),  # 0.8 m ahead: x in [1.5, 2.5], y in [1.4, 2.2]
    _cyl("can_a", "can", 1.8, 1.6, 0.72),  # lateral +0.2 (left of the robot); world y 1.6
    _cyl("can_b", "can", 2.2, 1.8, 0.72),  # lateral -0.2 (right); world y 1.8: "left" if yaw were ignored
    # a rack on the robot's left (x = 1: lateral +1) at world y 1.4, three boards grouped by attributes.unit
    _box("shelf_l_low", "shelf", 1.0, 1.4, 0.385, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    _box("shelf_l_mid", "shelf", 1.0, 1.4, 0.785, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    _box("shelf_l_top", "shelf", 1.0, 1.4, 1.185, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    # a rack on the robot's right (x = 3: lateral -1) at world y 1.8, two stacked boards
    _box("shelf_r_low", "shelf", 3.0, 1.8, 0.385, 0.4, 0.8, 0.03),
    _box("shelf_r_top", "shelf", 3.0, 1.8, 0.985, 0.4, 0.8, 0.03),
    _cyl("can_green", "can", 1.0, 1.4, 1.215, extra=", color: green"),  # left top board
    _cyl("can_plain", "can", 1.0, 1.5, 0.815),  # left middle board
    _cyl("can_red", "can", 3.0, 1.8, 0.415, extra=", color: red"),  # right bottom board
]
SCENE = parse_scene("name: turned\n" + ROBOT + "objects:\n" + "\n".join(OBJECTS) + "\n", "turned")


def test_lateral_is_the_y_coordinate_in_the_turned_and_moved_base_frame():
    o = {x.id: x for x in SCENE.objects}
    assert spatial.lateral(o["can_a"], SCENE) == pytest.approx(0.2)
    assert spatial.lateral(o["can_b"], SCENE) == pytest.approx(-0.2)
    assert spatial.lateral(o["shelf_l_top"], SCENE) == pytest.approx(1.0)
    assert spatial.lateral(o["can_red"], SCENE) == pytest.approx(-1.0)
    # a base at (2, 1) facing world -x (yaw pi): left is world -y; (1.0, 0.5) is 0.5 m to that side
    back = parse_scene("name: back\n" + ROBOT.replace("1.5707963267948966", str(math.pi)) + "objects:\n"
                       + _cyl("c", "can", 1.0, 0.5, 0.0) + "\n", "back")
    assert spatial.lateral(back.objects[0], back) == pytest.approx(0.5)


def test_distances_are_measured_from_the_base_not_the_origin():
    # can_a's footprint [1.767, 1.833] x [1.567, 1.633] is 0.167 m across and 0.567 m ahead of (2, 1)
    o = {x.id: x for x in SCENE.objects}
    p = spatial.robot_position(SCENE)
    assert tuple(p) == (2.0, 1.0, 0.0)
    assert spatial.distance_to_point(o["can_a"], p) == pytest.approx(math.hypot(0.2 - 0.033, 0.6 - 0.033))


CASES = [
    # the two cans on the table, 0.4 m apart across the robot: can_a on its left, can_b on its right
    ("pick up the left can on the table", pick("can_a")),
    ("grab the right can on the table", pick("can_b")),
    # all five cans by lateral: +1, +1 (left rack), +0.2, -0.2 (table), -1 (right rack); range 2, thirds at +-1/3
    ("pick up the can on the right", pick("can_red")),
    ("pick up the leftmost can", pick("can_green", "can_plain")),
    ("grab the rightmost can", pick("can_red")),
    # racks as units: the x = 1 rack is the left one, whatever its world y
    ("pick up the can on the left shelf", pick("can_green", "can_plain")),
    ("grab the can on the right shelf", pick("can_red")),
    ("pick up the can that is on the top left shelf", pick("can_green")),
    ("put the green can on the right shelf", place(["can_green"], ["shelf_r_low", "shelf_r_top"])),
    ("put the red can on the middle shelf", place(["can_red"], ["shelf_l_mid"])),
    # nearest to the base at (2, 1): can_a 0.59 m, can_b 0.79, can_green 1.03, can_plain 1.08, can_red 1.23
    # (from the origin it would be can_green, 1.67 m)
    ("pick up the nearest can", pick("can_a")),
    ("grab the farthest can", pick("can_red")),
]


@pytest.mark.parametrize("request_text, expected", CASES, ids=[c[0] for c in CASES])
def test_turned_base_grounds_by_hand(request_text, expected):
    g = ground(request_text, SCENE)
    assert {i.id for i in g.interpretations} == expected
