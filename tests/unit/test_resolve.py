"""grounding.resolve rules the table-driven cases do not reach (found by mutation testing, issue 32).

Each scene is small and every expectation is worked out by hand in the comments.
"""

from __future__ import annotations

import pytest

from grounding import ground
from grounding.model import GroundingError
from grounding.resolve import _id_number
from tests.unit.test_grounding import _box, _cyl, _fetch_scene, park, pick, scene

# three cans on a long table, at the same height; ahead is +x, left +y (base at the origin, yaw 0)
SPREAD = _fetch_scene("spread", [
    _box("table_1", "table", 1.0, 0.0, 0.68, 1.0, 3.0, 0.04),
    _cyl("can_1", "can", 0.7, 0.0, 0.72),
    _cyl("can_2", "can", 1.4, 0.1, 0.72),  # 0.7 m further along x than can_1
    _cyl("can_3", "can", 0.9, -0.5, 0.72),
])
# three cans in a line across the robot's view (lateral +0.5, 0, -0.5), the right one marked side: left
MARKED = _fetch_scene("marked", [
    _box("table_1", "table", 0.8, 0.0, 0.68, 0.8, 1.6, 0.04),
    _cyl("can_l", "can", 0.8, 0.5, 0.72),
    _cyl("can_m", "can", 0.8, 0.0, 0.72),
    _cyl("can_r", "can", 0.8, -0.5, 0.72, extra=", attributes: {side: left}"),
])


def ids(text, sc):
    return {i.id for i in ground(text, sc).interpretations}


def test_an_ordinal_counts_objects_in_scene_order_not_along_rows():
    # only parking spots count along their rows; cans 0.7 m apart along x would be rows of 1 and 2 cans
    assert ids("pick up the third can", SPREAD) == pick("can_3")
    assert ids("pick up the second can", SPREAD) == pick("can_2")
    with pytest.raises(GroundingError, match="only 3 cans"):
        ground("pick up the fourth can", SPREAD)


def test_the_middle_object_by_side_when_heights_are_equal():
    # equal heights: no vertical thirds, so "middle" is the lateral middle (0 of +0.5 .. -0.5)
    assert ids("pick up the middle can", MARKED) == pick("can_m")


def test_explicit_side_attributes_win_over_geometry():
    # can_r stands on the right (-0.5) but says side: left
    assert ids("pick up the left can", MARKED) == pick("can_l", "can_r")
    with pytest.raises(GroundingError, match="no right can"):
        ground("pick up the right can", MARKED)


def test_the_floor_cannot_be_picked():
    with pytest.raises(GroundingError, match="^cannot pick up the floor$"):
        ground("pick up the floor", SPREAD)


def test_rows_by_distance_from_the_car():
    # lot: the car at (1, 5) facing +x; spots facing +x, so a row is a line across x: bay_a/bay_d (x 5, their
    # near edge 1.5 m ahead), bay_b (x 8, occupied) and bay_c (x 11). The nearest row is bay_a and bay_d; the
    # left row (lateral = y - 5) would be bay_b/bay_c's
    lot = scene("lot")
    assert ids("park in the nearest row", lot) == park("bay_a", "bay_d")
    assert ids("park in the farthest row", lot) == park("bay_c")
    assert ids("park in the left row", lot) == park("bay_c")


def test_a_row_word_that_picks_no_side_does_not_crash():
    # "middle" names no side of a row: only GroundingError may escape, and what grounds is a free spot
    lot = scene("lot")
    try:
        got = ids("park in the middle row", lot)
    except GroundingError:
        return
    assert got <= park("bay_a", "bay_c", "bay_d")


def test_an_id_range_over_ids_without_numbers_is_refused_in_one_line():
    with pytest.raises(GroundingError, match="no 'spots 1 to 3' in this scene"):
        ground("park in spots 1 to 3", scene("lot"))


def test_an_occupied_spot_is_never_a_goal():
    lot = scene("lot")
    with pytest.raises(GroundingError, match="occupied spots are never goals"):
        ground("park in the occupied spot", lot)
    with pytest.raises(GroundingError, match="bay_b is occupied; free ones: bay_a, bay_c, bay_d"):
        ground("park in bay_b", lot)
    g = ground("park in a free spot", lot)
    assert {i.id for i in g.interpretations} == park("bay_a", "bay_c", "bay_d")
    assert not any("ignored" in n for n in g.notes)


@pytest.mark.parametrize("object_id,number", [("spot_b12", 12), ("spot_12b", 12), ("bay3_x", 3), ("spot_7", 7),
                                              ("bay_a", None), ("spot", None)])
def test_the_trailing_number_of_an_id(object_id, number):
    assert _id_number(object_id) == number
