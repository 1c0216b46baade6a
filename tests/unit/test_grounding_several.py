"""Grounding requests for several objects (issue #30): groups, counts, conjunctions, clearing, already there."""

from pathlib import Path

import pytest

from grounding import ground
from grounding.model import GroundingError
from lazyground.scene import load_scene

SCENE = load_scene(Path(__file__).parents[1] / "data/scenes/panda_cups.yaml")


def groups(text):
    return [(g.phrase, set(g.objects), g.count, set(g.already)) for g in ground(text, SCENE).groups]


@pytest.mark.parametrize("text, expected", [
    ("put all the cups on the table", [("all the cups", {"cup_a", "cup_b", "cup_t"}, None, {"cup_t"})]),
    ("put the cups on the table", [("the cups", {"cup_a", "cup_b", "cup_t"}, None, {"cup_t"})]),
    ("put every cup on the counter", [("every cup", {"cup_a", "cup_b", "cup_t"}, None, {"cup_a", "cup_b"})]),
    ("put two cups on the shelf", [("two cups", {"cup_a", "cup_b", "cup_t"}, 2, set())]),
    ("put both cups on the shelf", [("both cups", {"cup_a", "cup_b", "cup_t"}, 2, set())]),
    ("put a couple of cups on the shelf", [("a couple of cups", {"cup_a", "cup_b", "cup_t"}, 2, set())]),
    ("put a cup and a box on the shelf", [("a cup", {"cup_a", "cup_b", "cup_t"}, 1, set()),
                                          ("a box", {"box_s"}, 1, set())]),
    ("clear the table", [("everything on table", {"cup_t", "box_s", "can_t"}, None, set())]),
])
def test_groups(text, expected):
    assert groups(text) == expected


def test_clearing_goes_to_the_stated_surface_or_any_other():
    assert {i.target for i in ground("clear the table onto the counter", SCENE).interpretations} == {"counter"}
    assert {i.target for i in ground("clear the table", SCENE).interpretations} == {"counter", "shelf"}


def test_one_object_has_no_groups():
    assert ground("put a cup on the table", SCENE).groups == ()


@pytest.mark.parametrize("text, message", [
    ("put four cups on the shelf", "'four cups' asks for 4; the scene has 3"),
    ("pick up two cups", "not supported: 'two cups' asks for several objects; the robot handles one at a time"),
    ("pick up a cup and a box", "not supported: 'and' joins two objects or actions"),
    ("clear the counter onto the counter", "nowhere to put what is on counter"),
])
def test_refused(text, message):
    with pytest.raises(GroundingError) as info:
        ground(text, SCENE)
    assert str(info.value).startswith(message), str(info.value)
