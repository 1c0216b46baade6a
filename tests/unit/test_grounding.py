"""Table-driven grounding tests: each phrasing on a scene -> the exact set of interpretation ids.

The inline scenes below are shared by the other test_grounding_* files.
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from functools import lru_cache
from pathlib import Path

import pytest

from grounding import Grounding, ground
from lazyground.scene import load_scene, parse_scene

REPO = Path(__file__).resolve().parents[2]


def _cyl(id, type, x, y, z_bottom, r=0.033, length=0.12, extra=""):
    return f"- {{id: {id}, type: {type}, geometry: {{cylinder: {{radius: {r}, length: {length}}}}}, pose: {{xyz: [{x}, {y}, {z_bottom + length / 2:.4f}]}}{extra}}}"


def _box(id, type, x, y, z_bottom, sx, sy, sz, extra=""):
    return f"- {{id: {id}, type: {type}, geometry: {{box: [{sx}, {sy}, {sz}]}}, pose: {{xyz: [{x}, {y}, {z_bottom + sz / 2:.4f}]}}{extra}}}"


FETCH = textwrap.dedent("""\
    robot:
      model: fetch
      base: {xyz: [0, 0, 0]}
      end_effector: gripper_link
      start: {torso_lift_joint: 0.05}
    """)

# A table ahead (two cans, a small box), a left rack of three boards grouped by
# attributes.unit, a right rack of two boards grouped by their stacked footprints,
# and a big box on the floor. Every box fits the Fetch's 0.10 m opening across one axis
# (grasps exist only where the object fits: grounding/grasps.py).
KITCHEN = [
    _box("table_1", "table", 0.8, 0.0, 0.68, 0.8, 1.0, 0.04),
    _cyl("can_red", "can", 0.7, 0.2, 0.72, extra=", color: red"),
    _cyl("can_blue", "can", 0.7, -0.2, 0.72, extra=", color: blue"),
    _box("box_small", "box", 0.9, 0.0, 0.72, 0.05, 0.05, 0.05, extra=", color: brown"),
    _box("shelf_l_low", "shelf", 0.6, 1.0, 0.385, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    _box("shelf_l_mid", "shelf", 0.6, 1.0, 0.785, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    _box("shelf_l_top", "shelf", 0.6, 1.0, 1.185, 0.4, 0.8, 0.03, extra=", attributes: {unit: left_rack}"),
    _box("shelf_r_low", "shelf", 0.6, -1.0, 0.385, 0.4, 0.8, 0.03),
    _box("shelf_r_top", "shelf", 0.6, -1.0, 0.985, 0.4, 0.8, 0.03),
    _cyl("can_green", "can", 0.6, 1.1, 1.215, extra=", color: green"),
    _cyl("can_plain", "can", 0.6, 0.9, 0.815),
    _cyl("can_red2", "can", 0.6, -1.0, 0.415, extra=", color: red"),
    _box("box_mid", "box", 0.6, 0.8, 0.415, 0.08, 0.08, 0.12),
    _box("box_big", "box", 1.6, 0.5, 0.0, 0.3, 0.085, 0.3),
]

# A counter with two cups and a branded bottle; a desk (a "table") with a cup and a bottle.
CAFE = [
    _box("counter_1", "counter", 1.0, 0.0, 0.0, 0.6, 1.6, 0.9),
    _cyl("cup_white", "cup", 0.9, 0.4, 0.9, r=0.04, length=0.1, extra=", color: white"),
    _cyl("cup_black", "cup", 0.9, -0.4, 0.9, r=0.04, length=0.1, extra=", color: black, size: large"),
    _cyl("bottle_fizz", "bottle", 1.0, 0.0, 0.9, r=0.035, length=0.25, extra=", color: green, attributes: {brand: fizz}"),
    _box("desk_1", "table", 0.0, 1.2, 0.68, 0.6, 0.6, 0.04),
    _cyl("cup_red", "cup", 0.0, 1.1, 0.72, r=0.04, length=0.1, extra=", color: red"),
    _cyl("bottle_plain", "bottle", 0.1, 1.3, 0.72, r=0.035, length=0.25, extra=", color: grey"),
]

LOT = textwrap.dedent("""\
    name: lot
    robot: {model: car, start: {car_x: 1.0, car_y: 5.0, car_qz: 0.0}}
    objects:
    - {id: bay_a, type: parking_spot, geometry: {box: [5, 2.5, 0.05]}, pose: {xyz: [5, 8, 0]}}
    - {id: bay_b, type: parking_spot, geometry: {box: [5, 2.5, 0.05]}, pose: {xyz: [8, 8, 0]}, occupied: true}
    - {id: bay_c, type: parking_spot, geometry: {box: [5, 2.5, 0.05]}, pose: {xyz: [11, 8, 0]}}
    - {id: bay_d, type: parking_spot, geometry: {box: [5, 2.5, 0.05]}, pose: {xyz: [5, 2, 0]}}
    """)


def _fetch_scene(name: str, objects: list[str]):
    return parse_scene(f"name: {name}\n{FETCH}objects:\n" + "\n".join(objects) + "\n", name)


@lru_cache(maxsize=None)
def scene(name: str):
    """The test scenes by name: kitchen, cafe, lot, parking_1 (yaml_scenes/parking_1.yaml)."""
    if name == "kitchen":
        return _fetch_scene("kitchen", KITCHEN)
    if name == "cafe":
        return _fetch_scene("cafe", CAFE)
    if name == "lot":
        return parse_scene(LOT, "lot")
    return load_scene(REPO / "yaml_scenes" / f"{name}.yaml")


SCENES = ("kitchen", "cafe", "lot", "parking_1")
ALL_CANS = {"can_red", "can_blue", "can_green", "can_plain", "can_red2"}
BOXES = {"box_small", "box_mid", "box_big"}
SHELVES = {"shelf_l_low", "shelf_l_mid", "shelf_l_top", "shelf_r_low", "shelf_r_top"}
CUPS = {"cup_white", "cup_black", "cup_red"}
P1_FREE = {"spot_b1", "spot_t3", "spot_b9", "spot_t10"}


def pick(*ids):
    return {f"pick:{i}" for i in ids}


def place(objs, targets):
    return {f"place:{o}:{t}" for o in objs for t in targets}


def park(*ids):
    return {f"park:{i}" for i in ids}


CASES = [
    # --- pick: verbs, politeness, determiners -----------------------------------------------
    ("kitchen", "pick up a can", pick(*ALL_CANS)),
    ("kitchen", "grab a can", pick(*ALL_CANS)),
    ("kitchen", "Grab a can.", pick(*ALL_CANS)),
    ("kitchen", "take the box", pick(*BOXES)),
    ("kitchen", "lift any box", pick(*BOXES)),
    ("kitchen", "could you please pick up a can?", pick(*ALL_CANS)),
    ("kitchen", "please grab the box", pick(*BOXES)),
    ("kitchen", "can you pick up a tin?", pick(*ALL_CANS)),
    ("kitchen", "would you kindly fetch me a soda can, thanks", pick(*ALL_CANS)),
    ("kitchen", "I want a can", pick(*ALL_CANS)),
    ("kitchen", "i'd like one of the cans please", pick(*ALL_CANS)),
    ("kitchen", "pick up one of the cans", pick(*ALL_CANS)),
    ("kitchen", "get any of the cubes", pick(*BOXES)),
    ("kitchen", "grasp a carton", pick(*BOXES)),
    ("kitchen", "pick the blue can up", pick("can_blue")),
    ("kitchen", "pick up 1 block", pick(*BOXES)),
    ("kitchen", "hey robot, bring me the red tin now", pick("can_red", "can_red2")),
    ("kitchen", "pick up can_green", pick("can_green")),
    # --- colour, size, superlatives, wildcards --------------------------------------------------
    ("kitchen", "grab the red can", pick("can_red", "can_red2")),
    ("kitchen", "pick up the green soda", pick("can_green")),
    ("kitchen", "pick up the small box", pick("box_small")),
    ("kitchen", "take the little cube", pick("box_small")),
    ("kitchen", "pick up the big box", pick("box_big")),
    ("kitchen", "get the medium sized box", pick("box_mid")),
    ("kitchen", "pick up the biggest box", pick("box_big")),
    ("kitchen", "fetch the smallest carton", pick("box_small")),
    ("kitchen", "pick up the red one", pick("can_red", "can_red2")),
    ("kitchen", "grab the brown thing", pick("box_small")),
    ("kitchen", "pick up the can or the box", pick(*ALL_CANS, *BOXES)),
    # --- location: support relations, racks, left/right/top --------------------------------------
    ("kitchen", "a can on the table", pick("can_red", "can_blue")),  # a noun phrase alone: get it (#29)
    ("kitchen", "the green soda, please", pick("can_green")),
    ("lot", "bay c please", park("bay_c")),
    ("kitchen", "pick up a can on the table", pick("can_red", "can_blue")),
    ("kitchen", "grab the can on the desk", pick("can_red", "can_blue")),
    ("kitchen", "get a can from the shelf", pick("can_green", "can_plain", "can_red2")),
    ("kitchen", "take a can off the rack", pick("can_green", "can_plain", "can_red2")),
    ("kitchen", "pick up the can on the left shelf", pick("can_green", "can_plain")),
    ("kitchen", "grab the can on the right shelf", pick("can_red2")),
    ("kitchen", "pick up a can from the top shelf", pick("can_green")),
    ("kitchen", "grab a can from the middle shelf", pick("can_plain")),
    ("kitchen", "get the box on the bottom shelf", pick("box_mid")),
    ("kitchen", "pick up a box on the floor", pick("box_big")),
    ("kitchen", "pick up the can that is on the top left shelf", pick("can_green")),
    ("kitchen", "grab the can on the shelf on the right", pick("can_red2")),
    ("kitchen", "pick up the left can on the table", pick("can_red")),
    ("kitchen", "grab the can on the table on the right", pick("can_red", "can_blue")),  # one table: 'right' does not narrow
    ("kitchen", "pick up the can on the right", pick("can_red2")),
    ("kitchen", "pick up the highest can", pick("can_green")),
    ("kitchen", "grab the red can sitting on the table", pick("can_red")),
    # --- place ------------------------------------------------------------------------------------
    ("kitchen", "put a can on the table", place(ALL_CANS, ["table_1"])),
    ("kitchen", "place the box onto the table", place(BOXES, ["table_1"])),
    ("kitchen", "set a can on the shelf", place(ALL_CANS, SHELVES)),
    ("kitchen", "put the small box on the top shelf", place(["box_small"], ["shelf_l_top", "shelf_r_top"])),
    ("kitchen", "put the blue can on the left top shelf", place(["can_blue"], ["shelf_l_top"])),
    ("kitchen", "move the red can from the table to the right shelf", place(["can_red"], ["shelf_r_low", "shelf_r_top"])),
    ("kitchen", "take the green can to the desk", place(["can_green"], ["table_1"])),
    ("kitchen", "grab the blue can and put it on the middle shelf", place(["can_blue"], ["shelf_l_mid"])),
    ("kitchen", "put the can on the table on the bottom shelf", place(["can_red", "can_blue"], ["shelf_l_low", "shelf_r_low"])),
    ("kitchen", "please put down the big box on the table", place(["box_big"], ["table_1"])),
    ("kitchen", "put the red can into the rack on the left", place(["can_red", "can_red2"], ["shelf_l_low", "shelf_l_mid", "shelf_l_top"])),
    # --- cafe: cups, mugs, bottles, counters, explicit sizes, attributes ----------------------------
    ("cafe", "get me a cup", pick(*CUPS)),
    ("cafe", "grab a mug", pick(*CUPS)),
    ("cafe", "fetch one of the bottles", pick("bottle_fizz", "bottle_plain")),
    ("cafe", "the cup on the counter, please: pick it up", None),
    ("cafe", "pick up the cup on the counter", pick("cup_white", "cup_black")),
    ("cafe", "grab the mug on the left on the kitchen counter", pick("cup_white")),
    ("cafe", "grab the mug on the kitchen counter on the left", pick("cup_white", "cup_black")),  # 'on the left' narrows the counter
    ("cafe", "pick up the large cup", pick("cup_black")),
    ("cafe", "get the big mug", pick("cup_black")),
    ("cafe", "pick up the gray bottle", pick("bottle_plain")),
    ("cafe", "pick up the grey bottle", pick("bottle_plain")),
    ("cafe", "grab the fizz bottle", pick("bottle_fizz")),
    ("cafe", "get a cup from the desk", pick("cup_red")),
    ("cafe", "put a cup on the table", place(CUPS, ["desk_1"])),
    ("cafe", "put the red mug on the counter", place(["cup_red"], ["counter_1"])),
    ("cafe", "place a bottle on the desk or the counter", place(["bottle_fizz", "bottle_plain"], ["desk_1", "counter_1"])),
    ("cafe", "take the white cup to the desk", place(["cup_white"], ["desk_1"])),
    # --- parking ----------------------------------------------------------------------------------
    ("lot", "park", park("bay_a", "bay_c", "bay_d")),
    ("lot", "park the car", park("bay_a", "bay_c", "bay_d")),
    ("lot", "find a parking spot", park("bay_a", "bay_c", "bay_d")),
    ("lot", "park in a free spot", park("bay_a", "bay_c", "bay_d")),
    ("lot", "Please park it.", park("bay_a", "bay_c", "bay_d")),
    ("lot", "find me an empty parking space", park("bay_a", "bay_c", "bay_d")),
    ("lot", "park in bay_c", park("bay_c")),
    ("lot", "park in bay_a or bay_c", park("bay_a", "bay_c")),
    ("lot", "park on the left", park("bay_a", "bay_c")),
    ("lot", "park in the rightmost bay", park("bay_d")),
    ("lot", "pull into one of the free bays", park("bay_a", "bay_c", "bay_d")),
    ("lot", "take an available spot", park("bay_a", "bay_c", "bay_d")),
    ("parking_1", "park", park(*P1_FREE)),
    ("parking_1", "park the car", park(*P1_FREE)),
    ("parking_1", "find a parking spot", park(*P1_FREE)),
    ("parking_1", "park in a free spot", park(*P1_FREE)),
    ("parking_1", "could you park the car in a free parking bay please", park(*P1_FREE)),
    ("parking_1", "park in spot_b9", park("spot_b9")),
    ("parking_1", "drive to spot_t10", park("spot_t10")),
]
CASES = [c for c in CASES if c[2] is not None]


@pytest.mark.parametrize("scene_name, request_text, expected", CASES, ids=[f"{s}:{r}" for s, r, _ in CASES])
def test_phrasing_grounds_to_exact_interpretations(scene_name, request_text, expected):
    g = ground(request_text, scene(scene_name))
    assert {i.id for i in g.interpretations} == expected
    assert len(g.interpretations) == len(expected)  # no duplicates
    assert g.action == next(iter(expected)).split(":")[0]


def test_enough_phrasings():
    assert len(CASES) >= 60


def test_interpretations_carry_goal_regions():
    g = ground("put the blue can on the table", scene("kitchen"))
    (i,) = g.interpretations
    assert (i.action, i.objects, i.target) == ("place", ("can_blue",), "table_1")
    # a can: the top grasp, side grasps at two heights and the angled grasp (lazyground/scene/types.yaml)
    assert [r.label for r in i.goal_regions] == ["top", "side 35%", "side 65%", "angled"]
    assert all(r.kind == "workspace" and r.object == "can_blue" for r in i.goal_regions)
    assert [r.kind for r in i.place_regions] == ["placement"] and i.place_regions[0].object == "table_1"
    assert all(r.interpretation == i.id for r in i.goal_regions + i.place_regions)
    spot = ground("park in bay_c", scene("lot")).interpretations[0]
    assert [r.kind for r in spot.goal_regions] == ["config", "config"]


def test_ambiguity_is_kept_with_a_note():
    g = ground("pick up the can on the table", scene("kitchen"))
    assert g.ambiguous and len(g.interpretations) == 2
    assert any("matches 2 cans" in n and "all kept" in n for n in g.notes)
    single = ground("pick up the blue can", scene("kitchen"))
    assert not single.ambiguous and single.notes == ()


def test_words_that_do_not_narrow_leave_a_note():
    g = ground("pick up the can on the table on the right", scene("kitchen"))
    assert any("'right' ignored" in n for n in g.notes)


def test_to_json_has_the_documented_shape():
    g = ground("put the blue can on the table", scene("kitchen"))
    data = json.loads(json.dumps(g.to_json()))
    assert {"request", "action", "interpretations", "ambiguous"} <= set(data)
    (i,) = data["interpretations"]
    assert {"id", "action", "objects", "target", "goal_regions"} <= set(i)
    assert i["target"] == "table_1" and i["goal_regions"][0]["kind"] == "workspace"
    assert isinstance(ground("park", scene("lot")), Grounding)


def test_cli_ground_json(capsys):
    from lazyground.cli import main

    assert main(["ground", str(REPO / "yaml_scenes" / "parking_1.yaml"), "find a parking spot", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["action"] == "park" and data["ambiguous"] is True
    assert {i["id"] for i in data["interpretations"]} == park(*P1_FREE)
    assert main(["ground", str(REPO / "yaml_scenes" / "parking_1.yaml"), "pick up a bottle"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: no 'bottle' in this scene") and "\n" not in err


def test_user_lexicon_extends_the_synonyms(tmp_path, monkeypatch):
    from grounding import load_lexicon

    lex = load_lexicon(extra={"nouns": {"can": ["pop"]}, "verbs": {"pick": ["snag"]}})
    g = ground("snag a pop", scene("kitchen"), lexicon=lex)
    assert {i.id for i in g.interpretations} == pick(*ALL_CANS)
    extra = tmp_path / "words.yaml"
    extra.write_text("colours: {red: [crimson]}\n")
    monkeypatch.setenv("LAZYGROUND_LEXICON", str(extra))
    assert {i.id for i in ground("grab the crimson can", scene("kitchen")).interpretations} == pick("can_red", "can_red2")


def test_lexicon_rejects_a_word_with_two_meanings():
    from grounding import load_lexicon

    with pytest.raises(ValueError, match="'grab' is both"):
        load_lexicon(extra={"nouns": {"can": ["grab"]}})


def test_grounding_imports_no_pydrake():
    code = "import grounding, sys; assert not any(m.startswith('pydrake') for m in sys.modules), 'pydrake imported'"
    subprocess.run([sys.executable, "-c", code], check=True, cwd=REPO, timeout=60)
