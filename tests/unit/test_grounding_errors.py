"""Errors that teach: one line naming the problem and what the scene has instead."""

from __future__ import annotations

import pytest

from grounding import GroundingError, ground
from tests.unit.test_grounding import scene

ERRORS = [
    # no match: name the word and list what the scene has
    # several objects: more than the scene holds (picking up two cans is planned: one is put down, #30)
    ("kitchen", "pick up 9 cans", "'9 cans' asks for 9; the scene has 5 that fit"),
    ("kitchen", "fetch a bottle", "no 'bottle' in this scene; it has: table x1, can x5, box x3, shelf x5"),
    ("cafe", "grab a can", "no 'can' in this scene; it has: counter x1, cup x3, bottle x2, table x1"),
    ("lot", "pick up a cup", "no 'cup' in this scene; it has: parking_spot x4"),
    ("kitchen", "park", "no parking spot in this scene; it has: table x1, can x5, box x3, shelf x5"),
    # a filter that removes everything: say which, and what is there
    ("kitchen", "pick up the yellow can", "no yellow can; cans here are: red x2, blue x1, green x1, unknown colour x1"),
    ("kitchen", "pick up the red can on the top shelf", "no red can on the top shelf; cans on the top shelf are: green x1"),
    ("kitchen", "grab a box on the table on the left", None),  # table: 'left' does not narrow -> grounds
    ("kitchen", "pick up a can from the floor", "no can from the floor; cans here are: on the table x2, on the top left shelf x1, on the middle left shelf x1, on the bottom right shelf x1"),
    ("kitchen", "put a can on the middle shelf on the right", "no middle shelf on the right; middle shelves here are: left/middle x1"),
    ("cafe", "pick up the small cup", "no small cup; cups here are: unknown size x2, large x1"),
    ("cafe", "pick up the shiny cup", "unknown word 'shiny': not a colour, size or position, and no object here has it as an attribute"),
    ("cafe", "pick up the fizz cup", "no fizz cup; cups here are: not 'fizz' x3"),
    # parking spots
    ("lot", "park in bay_b", "bay_b is occupied; free ones: bay_a, bay_c, bay_d"),
    ("lot", "park in a taken spot", "not supported: parking in a spot that is 'taken'; occupied spots are never goals"),
    ("lot", "park the can", None),
    # unknown words and verbs: name the word, list the verbs
    ("kitchen", "frobnicate the can", "unknown word 'frobnicate'; supported verbs: pick up, grab, take, get, fetch, lift, grasp, put, place, set, move, park (see docs/requests.md)"),
    ("kitchen", "on the table", "a request starts with a verb, not 'on'; supported verbs:"),
    ("kitchen", "pick up the widget", "unknown word 'widget'; objects here: table x1, can x5, box x3, shelf x5; verbs:"),
    ("kitchen", "pick up the can quietly", "unknown word 'quietly'; objects here:"),
    # unsupported forms
    ("kitchen", "do not pick up the red can", "not supported: a negated action ('pick up' after 'not')"),
    ("kitchen", "pick it up", "not supported: 'it' (nothing to refer back to)"),
    ("kitchen", "pick up the can put the box", "not supported: a second verb 'put'"),
    # wrong roles
    ("kitchen", "lift the table", "cannot pick up a table: type 'table' has no 'pick' definition in lazyground/scene/types.yaml"),
    ("kitchen", "put the can on the can", None),
    ("kitchen", "put the red can on a box", "cannot put things on a box: type 'box' has no 'support' definition in lazyground/scene/types.yaml"),
    ("kitchen", "put a can", "'put' needs a place, e.g. 'put the can on the table'"),
    ("kitchen", "grab", "'grab' needs an object, e.g. 'grab a can'"),
    ("kitchen", "pick up the car", "cannot pick up 'the car': that is the robot"),
    ("kitchen", "put the can on", "expected an object after 'on'"),
    # text limits
    ("kitchen", "", "empty request"),
    ("kitchen", "   ?!.  ", "empty request"),
    ("kitchen", "please", "empty request"),
    ("kitchen", "pick up a can " * 40, "request too long: 560 characters (limit 500)"),
    ("kitchen", "pick up a caf\u00e9 can", "only plain ASCII requests are understood; found '\u00e9' at position 13"),
]


@pytest.mark.parametrize("scene_name, text, message", [e for e in ERRORS if e[2]], ids=[e[1][:40] for e in ERRORS if e[2]])
def test_error_message(scene_name, text, message):
    with pytest.raises(GroundingError) as info:
        ground(text, scene(scene_name))
    got = str(info.value)
    assert "\n" not in got
    assert got.startswith(message), got


def test_words_that_cannot_narrow_ground_instead_of_failing():
    g = ground("grab a box on the table on the left", scene("kitchen"))
    assert {i.id for i in g.interpretations} == {"pick:box_small"}
    assert any("'left' ignored" in n for n in g.notes)


def test_park_needs_a_spot():
    with pytest.raises(GroundingError, match="'park' needs a parking spot, not 'the can'"):
        ground("park the can", scene("kitchen"))


def test_an_object_is_never_placed_on_itself():
    with pytest.raises(GroundingError, match="cannot put things on a can"):
        ground("put the can on the can", scene("kitchen"))


def test_a_dropped_alternative_is_noted():
    g = ground("pick up the can or the bottle", scene("kitchen"))
    assert len(g.interpretations) == 5
    assert any("dropped an alternative: no 'bottle'" in n for n in g.notes)


def test_non_string_request():
    with pytest.raises(GroundingError, match="a request is text"):
        ground(None, scene("kitchen"))
