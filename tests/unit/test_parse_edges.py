"""grounding.parse cases the table-driven tests did not pin (found by mutation testing, issue 32): a negated
second action at the end of the request, ids joined by "or", a landmark of "nearest", a headless ordinal's note."""

from __future__ import annotations

import pytest

from grounding import ground
from grounding.model import GroundingError
from tests.unit.test_grounding import park, pick, scene


@pytest.mark.parametrize("text,verb", [("pick up the can and don't pick up the box", "pick up"),
                                       ("pick up the can and do not grab", "grab")])  # the verb the last word
def test_a_negated_second_action_is_refused_naming_its_verb(text, verb):
    with pytest.raises(GroundingError, match=rf"^not supported: a negated action \('{verb}' after 'not'\); say what to do instead$"):
        ground(text, scene("kitchen"))


def test_nearest_a_landmark_is_measured_from_the_landmark():
    # kitchen: can_red (0.7, 0.2) and can_blue (0.7, -0.2) are equally near the robot; box_big's footprint
    # (x 1.45..1.75, y 0.4575..0.5425) is 0.79 m from can_red's centre and 1.00 m from can_blue's
    assert {i.id for i in ground("pick up the can nearest the box_big", scene("kitchen")).interpretations} == pick("can_red")
    assert {i.id for i in ground("pick up the can nearest me", scene("kitchen")).interpretations} == pick("can_red", "can_blue")


def test_ids_joined_by_or():
    g = ground("park in spot t3 or t10", scene("parking_1"))
    assert {i.id for i in g.interpretations} == park("spot_t3", "spot_t10")
    assert not any("dropped" in n for n in g.notes), g.notes


def test_a_headless_ordinal_names_the_spot_in_its_note():
    # parking_1: the second spot of row t (spot_t1) is occupied, of row b (spot_b1) free
    g = ground("park in the second", scene("parking_1"))
    assert {i.id for i in g.interpretations} == park("spot_b1")
    assert g.notes == ("the second spot of another row, spot_t1, is occupied: kept spot_b1",)
