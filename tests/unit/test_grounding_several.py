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
    ("pick up a cup and put a box on the shelf", "not supported: 'and' joins two objects or actions"),
    ("clear the counter onto the counter", "nowhere to put what is on counter"),
])
def test_refused(text, message):
    with pytest.raises(GroundingError) as info:
        ground(text, SCENE)
    assert str(info.value).startswith(message), str(info.value)


# --- picking up several (one gripper: every object but the last is put down first) ---------------

@pytest.mark.parametrize("text, expected", [
    ("pick up two cups", [("two cups", {"cup_a", "cup_b", "cup_t"}, 2, set())]),
    ("grab both cups", [("both cups", {"cup_a", "cup_b", "cup_t"}, 2, set())]),
    ("take all the cups", [("all the cups", {"cup_a", "cup_b", "cup_t"}, None, set())]),
    ("pick up a cup and a box", [("a cup", {"cup_a", "cup_b", "cup_t"}, 1, set()), ("a box", {"box_s"}, 1, set())]),
])
def test_picking_several_is_a_pick_with_groups(text, expected):
    g = ground(text, SCENE)
    assert g.action == "pick" and groups(text) == expected
    picks = {i.objects[0] for i in g.interpretations if i.action == "pick"}
    assert picks == set().union(*(x[1] for x in expected))  # every candidate may be the one held


def test_default_stow_is_every_other_surface_than_the_objects_own():
    g = ground("pick up two cups", SCENE)
    stows = {(i.objects[0], i.target) for i in g.interpretations if i.action == "place"}
    assert {t for o, t in stows if o == "cup_a"} == {"table", "shelf"}  # cup_a rests on the counter
    assert {t for o, t in stows if o == "cup_t"} == {"counter", "shelf"}
    assert any("put down first" in n for n in g.notes)


def test_declared_stow_surfaces():
    from dataclasses import replace

    g = ground("pick up two cups", replace(SCENE, stow=("shelf",)))
    assert {i.target for i in g.interpretations if i.action == "place"} == {"shelf"}
    with pytest.raises(GroundingError, match="stow: 'cup_b' is a cup, not a surface"):
        ground("pick up two cups", replace(SCENE, stow=("cup_b",)))


def test_stow_key_names_an_object_of_the_scene():
    from dataclasses import replace

    assert replace(SCENE, stow=("sofa",)).validate().startswith("stow[0]: 'sofa' is no object")
