"""Requests as people type them (#20): ids with spaces, ordinals, distances, spelling hints, scene type typos."""

from __future__ import annotations

import textwrap

import pytest

from grounding import GroundingError, ground
from grounding.regions import check_types
from lazyground.scene import load_scene, parse_scene
from tests.unit.test_grounding import REPO, scene

CANS_1 = "fetch_cans_1"

GROUNDS = [
    # ids typed with a space, in any case, split between letters and digits
    (CANS_1, "pick up can 2", {"pick:Can2"}),
    (CANS_1, "pick up the Can 2", {"pick:Can2"}),
    ("parking_1", "park in spot b1", {"park:spot_b1"}),
    ("parking_1", "park in spot B1", {"park:spot_b1"}),
    ("parking_1", "park in spot_b1", {"park:spot_b1"}),
    # ordinals count in scene-file order; "last" from the end
    (CANS_1, "pick up the second can", {"pick:Can2"}),
    (CANS_1, "grab the last can", {"pick:Can4"}),  # (its boxes, 0.2 m wide, fit no gripper: grounding/grasps.py)
    (CANS_1, "pick up the second can on the middle left shelf", {"pick:Can2"}),
    # distances: from the robot's base (Fetch at the origin), or from a named object
    (CANS_1, "pick up the nearest can", {"pick:Can3"}),
    (CANS_1, "pick up the farthest can", {"pick:Can4"}),
    (CANS_1, "pick up the can nearest the table", {"pick:Can3"}),
    (CANS_1, "pick up the can closest to the table", {"pick:Can3"}),
    (CANS_1, "pick up the can nearest to box 2", {"pick:Can4"}),
    # the car starts at (3.5, 8.25): spot_b1 is the closest free spot, spot_t10 the farthest
    ("parking_1", "park in the closest spot", {"park:spot_b1"}),
    ("parking_1", "park in the farthest spot", {"park:spot_t10"}),
]


def _scene(name: str):
    return load_scene(REPO / "yaml_scenes" / f"{name}.yaml") if name == CANS_1 else scene(name)


@pytest.mark.parametrize("name,text,expected", GROUNDS, ids=[g[1] for g in GROUNDS])
def test_typed_request_grounds(name, text, expected):
    got = {i.id for i in ground(text, _scene(name)).interpretations}
    assert got == expected


def test_nearest_spot_is_the_closest_free_centre():
    """The claim behind the table above, computed independently: min over free spots of |centre - car|."""
    sc = _scene("parking_1")
    car = (sc.robot.start["car_x"], sc.robot.start["car_y"])
    free = [o for o in sc.objects if o.type == "parking_spot" and not o.occupied]
    dist = {o.id: ((o.pose.xyz[0] - car[0]) ** 2 + (o.pose.xyz[1] - car[1]) ** 2) ** 0.5 for o in free}
    assert min(dist, key=dist.get) == "spot_b1"
    assert max(dist, key=dist.get) == "spot_t10"


ERRORS = [
    (CANS_1, "pikc up a can", "unknown word 'pikc'; did you mean 'pick'?"),
    (CANS_1, "pick up a cna", "unknown word 'cna'; did you mean 'can'?"),
    ("parking_1", "pakr", "unknown word 'pakr'; did you mean 'park'?"),
    ("parking_1", "park in b12", "unknown word 'b12'; ids here: spot_b0, spot_t0, spot_b1"),
    (CANS_1, "pick up can 7", "no 'can 7' in this scene; ids with 'can': Can1, Can2, Can3, Can4"),
    (CANS_1, "pick up the fifth can", "no fifth can: there are only 4 cans"),
    (CANS_1, "grab a can from the top shelf",
     "no can from the top shelf; cans here are: on the middle left shelf x2, on the table x1, on the middle right shelf x1"),
]


@pytest.mark.parametrize("name,text,message", ERRORS, ids=[e[1] for e in ERRORS])
def test_typed_request_errors(name, text, message):
    with pytest.raises(GroundingError) as info:
        ground(text, _scene(name))
    got = str(info.value)
    assert "\n" not in got and got.startswith(message), got


def test_location_breakdown_names_words_that_ground():
    """Every "on X" the breakdown offers works as a request and keeps exactly the cans it counted."""
    sc = _scene(CANS_1)
    with pytest.raises(GroundingError) as info:
        ground("grab a can from the top shelf", sc)
    breakdown = str(info.value).split("are: ", 1)[1]
    for part in breakdown.split(", "):
        where, count = part.rsplit(" x", 1)
        got = ground(f"grab a can {where.replace('on ', 'from ', 1)}", sc).interpretations
        assert len(got) == int(count), part


def test_refuses_counts_above_what_the_scene_holds():
    with pytest.raises(GroundingError, match="'5 cans' asks for 5; the scene has 4"):
        ground("pick up 5 cans", _scene(CANS_1))


TYPO = textwrap.dedent("""\
    name: typo
    robot: {model: car, start: {car_x: 1.0, car_y: 1.0, car_qz: 0.0}}
    objects:
    - {id: spot_a, type: parking_spot, geometry: {box: [5.0, 2.5, 0.01]}, pose: {xyz: [10.0, 5.0, 0.005]}}
    - {id: spot_b, type: parking_sopt, geometry: {box: [5.0, 2.5, 0.01]}, pose: {xyz: [10.0, 9.0, 0.005]}}
    """)


def test_undefined_object_type_is_an_error_with_a_suggestion():
    with pytest.raises(GroundingError) as info:
        ground("park", parse_scene(TYPO, "typo"))
    msg = str(info.value)
    assert msg.startswith("object 'spot_b': unknown type 'parking_sopt'; did you mean 'parking_spot'?"), msg
    assert "grasp_types: {parking_sopt: {}}" in msg


@pytest.mark.parametrize("typo", ["mug", "muggg"])
def test_a_type_named_by_a_word_of_another_suggests_that_type(typo, tmp_path):
    # issue 34: 'type: mug' said "unknown type 'mug'; (types: ...)", no file, no suggestion ('mug' is a word for a cup)
    path = tmp_path / "my_table.yaml"
    path.write_text(TYPO.replace("parking_sopt", typo))
    with pytest.raises(GroundingError) as info:
        ground("park", load_scene(path))
    msg = str(info.value)
    assert msg.startswith(f"object 'spot_b': unknown type {typo!r}; did you mean 'cup'?"), msg
    assert msg.endswith(f"({path} line 5)"), msg


def test_a_scene_declares_its_own_type():
    sc = parse_scene(TYPO + "grasp_types: {parking_sopt: {}}\n", "typo")
    assert {i.id for i in ground("park", sc).interpretations} == {"park:spot_a"}
    with pytest.raises(GroundingError, match="has no 'park' definition"):
        ground("park in spot_b", sc)


def test_a_type_starting_with_a_vowel_takes_an():
    # issue 34: "cannot park in a exit: type 'exit' has no 'park' definition"
    sc = parse_scene(TYPO.replace("parking_sopt", "exit") + "grasp_types: {exit: {}}\n", "typo")
    with pytest.raises(GroundingError, match="^cannot park in an exit: type 'exit'"):
        ground("park at the exit", sc)


def test_every_bundled_scene_declares_its_types():
    for path in sorted((REPO / "yaml_scenes").glob("*.yaml")):
        check_types(load_scene(path))
