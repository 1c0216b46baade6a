"""Rows of parking spots joined by "or" (issue 32's finding): "row t or b" names two rows, and a row given as an
alternative to a spot ("spot b1 or row t") means that row's free spots, not every free spot of the lot."""

from __future__ import annotations

import pytest

from grounding import ground
from tests.unit.test_grounding import park, scene

# parking_1's free spots, read from its YAML: spot_t3, spot_t10 in row t (+y), spot_b1, spot_b9 in row b
ROW_T = ("spot_t3", "spot_t10")
ROW_B = ("spot_b1", "spot_b9")


@pytest.mark.parametrize("text", ["park in row t or b", "park in row t or row b", "park in row b or t"])
def test_a_row_name_after_or_names_a_row(text):
    g = ground(text, scene("parking_1"))
    assert {i.id for i in g.interpretations} == park(*ROW_T, *ROW_B)
    assert not any("dropped" in n or "unknown" in n for n in g.notes), g.notes


@pytest.mark.parametrize("text", ["park in row t or spot b1", "park in spot b1 or row t"])
def test_a_row_beside_a_spot_means_that_rows_spots(text):
    g = ground(text, scene("parking_1"))
    assert {i.id for i in g.interpretations} == park(*ROW_T, "spot_b1")  # not spot_b9: row b was not asked for
    assert not any("dropped" in n for n in g.notes), g.notes


def test_one_row_is_unchanged():
    assert {i.id for i in ground("park in row t", scene("parking_1")).interpretations} == park(*ROW_T)
    assert {i.id for i in ground("park in row b", scene("parking_1")).interpretations} == park(*ROW_B)
