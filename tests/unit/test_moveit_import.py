"""MoveIt planning-scene import (lazyground.moveit, #15): the reference and corpus scenes, file kinds,
type rules, start states, meshes, atomic output. No pydrake: the start's collision check is off here
(tests/drake/test_moveit_drake.py covers it)."""

import math
import textwrap
from pathlib import Path

import pytest
import yaml

from lazyground.bench.moveit_corpus import CORPUS, REFERENCE, corpus_entries
from lazyground.moveit import ImportOptions, StartOptions, classify, convert_moveit, import_moveit_file, parse_rule, tokens, word_type
from lazyground.moveit.types import load_rules_file
from lazyground.scene import load_scene
from lazyground.typed_yaml import SceneError

REFERENCE_FILES = sorted(REFERENCE.glob("*.yml")) if REFERENCE.is_dir() else []
# a MoveIt planning scene of one wall in the robot's base frame (also tests/drake/test_robot_corpus.py)
ONE_WALL = textwrap.dedent("""\
    name: s
    world:
      collision_objects:
        - id: wall
          header: {frame_id: base_link}
          primitives: [{type: box, dimensions: [0.1, 1.0, 1.0]}]
          primitive_poses: [{position: {x: 1.5, y: 0.0, z: 0.5}, orientation: {x: 0, y: 0, z: 0, w: 1}}]
    """)
KITCHEN = ImportOptions(packages={"kitchen_description": CORPUS / "kitchen_description"})


def _import(path, tmp_path, options=ImportOptions(), name="scene"):
    return import_moveit_file(path, tmp_path / f"{name}.yaml", options, check_start=False)


@pytest.mark.skipif(not REFERENCE_FILES, reason="reference MoveIt scenes not available")
@pytest.mark.parametrize("path", REFERENCE_FILES, ids=lambda p: p.stem)
def test_reference_scene_converts_and_loads(path, tmp_path):
    result = _import(path, tmp_path)
    scene = load_scene(result.output)
    assert scene.robot.start["shoulder_pan_joint"] == pytest.approx(1.32)
    assert scene.robot.start["torso_lift_joint"] == pytest.approx(0.05)
    assert (scene.robot.end_effector.frame, scene.robot.end_effector.approach_axis) == ("gripper_link", "x")  # models/fetch/robot.yaml
    assert scene.planner.algorithm == "bidirectional" and scene.planner.edge_resolution == 0.05  # the robot's planner
    cans = scene.objects_of_type("can")
    assert cans and all(c.geometry.cylinder is not None for c in cans)
    if "scenario3" in path.stem:
        assert len(scene.objects_of_type("box")) == 5  # Cube1..5
        assert {"Shelf1_4", "Shelf1_5", "Shelf1_6"} <= {o.id for o in scene.obstacles}  # vertical boards
        assert {"Shelf1_1", "Shelf1_2"} <= {o.id for o in scene.objects_of_type("shelf")}
        bar = next(o for o in scene.obstacles if o.id == "Bar1")
        assert bar.pose.rpy[1] == pytest.approx(1.0826348, abs=1e-6)
    else:
        mesh = [w for w in result.summary.warnings if "mesh" in w]
        assert len(mesh) == 1 and "table_right" in mesh[0] and "1 of " in mesh[0]  # one warning with count and fraction
        assert result.summary.meshes_dropped == 1 and result.summary.objects_dropped == 1
        can1 = scene.object("Can1")  # MoveIt cylinder dimensions are [height, radius]
        assert can1.geometry.cylinder.length == pytest.approx(0.115)


@pytest.mark.parametrize("entry", corpus_entries(reference=Path("/nonexistent")), ids=lambda e: e.name)
def test_corpus_scene_imports_with_its_options(entry, tmp_path):
    options = ImportOptions(packages=entry.packages, start=StartOptions(request=str(entry.start_from) if entry.start_from else None))
    scene = load_scene(_import(entry.file, tmp_path, options).output)
    kind = "box" if "box" in entry.request else "can"
    assert scene.objects_of_type(kind), "the natural request needs an object to act on"
    assert all(0.3 < math.hypot(*o.pose.xyz[:2]) < 1.0 for o in scene.objects_of_type(kind))  # within the Fetch's reach


SMALL = """
    robot_state:
      joint_state:
        name: [torso_lift_joint, shoulder_pan_joint]
        position: [0.2, -0.5]
    world:
      collision_objects:
        - id: Mug7
          header: {frame_id: /base_link}
          pose: {position: [1.0, 0.0, 0.0], orientation: [0, 0, 0, 1]}
          primitives:
            - {type: cylinder, dimensions: [0.1, 0.04]}
          primitive_poses:
            - {position: {x: 0.0, y: 0.5, z: 0.8}, orientation: {x: 0, y: 0, z: 0.7071068, w: 0.7071068}}
        - id: Crate
          primitives: [{type: 1, dimensions: [0.08, 0.06, 0.1]}, {type: sphere, dimensions: [0.03]}]
          primitive_poses:
            - {position: [0.5, 0, 0.05], orientation: [0, 0, 0, 1]}
            - {position: [0.5, 0, 0.2], orientation: [0, 0, 0, 2]}
"""


def _yaml(text: str) -> dict:
    return yaml.safe_load(textwrap.dedent(text))


def test_small_scene_poses_types_and_start():
    scene, summary = convert_moveit(_yaml(SMALL), "small.yml")
    mug = next(o for o in scene["objects"] if o["id"] == "Mug7")
    assert mug["type"] == "cup"
    assert mug["pose"]["xyz"] == pytest.approx([1.0, 0.5, 0.8])  # object pose composed with the primitive pose
    assert mug["pose"]["rpy"][2] == pytest.approx(math.pi / 2)
    assert mug["geometry"] == {"cylinder": {"radius": 0.04, "length": 0.1}}
    crates = [o for o in scene["objects"] if o["id"].startswith("Crate")]
    assert [c["id"] for c in crates] == ["Crate_1", "Crate_2"] and all(c["type"] == "box" for c in crates)
    assert crates[1]["geometry"] == {"sphere": {"radius": 0.03}}
    assert any("Crate_2" in w and "norm 2.000000" in w for w in summary.warnings)
    assert scene["robot"]["start"]["torso_lift_joint"] == 0.2
    assert scene["robot"]["start"]["wrist_flex_joint"] == 1.66  # missing joints: the tucked pose, with a warning
    assert any("wrist_flex_joint" in w for w in summary.warnings)
    assert "planner" not in scene  # the robot.yaml's planner settings apply
    # base link, planned joints and the end effector with its axes come from the robot.yaml when the scene loads
    assert set(scene["robot"]) == {"model", "base", "start"}
    assert summary.types == {"cup": 1, "box": 2} and summary.start_source == "the scene's robot_state"


@pytest.mark.parametrize("oid, words, type_name", [
    ("table_leg_1", ["table", "leg", "1"], "obstacle"),
    ("shelf_vert", ["shelf", "vert"], "obstacle"),
    ("small_shelf_2", ["small", "shelf", "2"], "shelf"),
    ("Shelf1_4", ["shelf", "1", "4"], "shelf"),
    ("Can12", ["can", "12"], "can"),
    ("cube_a", ["cube", "a"], "box"),
    ("tableTop", ["table", "top"], "table"),
    ("Bar1", ["bar", "1"], "obstacle"),
    ("Cannon", ["cannon"], "obstacle"),  # a token, not a prefix
    ("Plant", ["plant"], "obstacle"),
])
def test_types_come_from_id_tokens(oid, words, type_name):
    assert tokens(oid) == words
    assert word_type(oid) == type_name


def test_geometry_overrules_the_words():
    assert classify("Shelf1_4", (0.5, 0.05, 1.2), "box", 0.10) [0] == "obstacle"  # a vertical board
    t, note = classify("table_3", (0.05, 0.05, 0.7), "box", 0.10)
    assert t == "obstacle" and "not a horizontal board" in note
    t, note = classify("box", (0.25, 0.25, 0.25), "box", 0.10)
    assert t == "obstacle" and "0.25 m wide, the gripper opens 0.10 m" in note
    assert classify("box_small", (0.06, 0.06, 0.1), "box", 0.10) == ("box", None)
    assert classify("Can1", (0.07, 0.07, 0.12), "cylinder", 0.10) == ("can", None)
    assert classify("counter", (1, 1, 1), "mesh", 0.10)[0] == "obstacle"


def test_user_rules_win_and_parse(tmp_path):
    rules = (parse_rule("^plant=can"), parse_rule("big=box"))
    assert classify("Plant", (0.07, 0.07, 0.1), "cylinder", 0.10, rules) == ("can", None)
    assert classify("big_box", (0.25, 0.25, 0.25), "box", 0.10, rules) == ("box", None)  # taken as given
    assert classify("plant_pot", (0, 0, 0), "mesh", 0.10, rules)[0] == "obstacle"  # but a mesh stays an obstacle
    path = tmp_path / "rules.yaml"
    path.write_text("'^tray': table\n")
    assert classify("tray_1", (0.05, 0.05, 0.5), "box", 0.1, load_rules_file(path))[0] == "table"
    for bad, words in (("noequals", "REGEX=TYPE"), ("(=can", "not a regular expression"), ("=can", "REGEX=TYPE")):
        with pytest.raises(SceneError, match=words):
            parse_rule(bad)
    path.write_text("- a\n")
    with pytest.raises(SceneError, match="mapping"):
        load_rules_file(path)
    path.write_text("'^tray': table\n'^tray': obstacle\n")  # audit8: the second rule replaced the first silently
    with pytest.raises(SceneError, match=r"duplicate key '\^tray' \(first at line 1\)"):
        load_rules_file(path)


@pytest.mark.parametrize("text, words", [
    ("start_state: {joint_state: {name: [a], position: [0]}}\ngroup_name: arm\n", "motion-plan request"),
    ("<?xml version='1.0'?>\n<robot name='r'><link name='a'/></robot>\n", "URDF"),
    ("<robot name='r'><group name='arm'/><group_state name='home' group='arm'/></robot>\n", "SRDF"),
    ("<sdf version='1.7'><model name='m'/></sdf>\n", "SDF"),
    ("[1, 2]\n", "not a MoveIt planning scene"),
    ("name: x\nrobot: {model: fetch}\n", "not a MoveIt planning scene (top-level keys: name, robot"),
    ("world: {collision_objects: []}\n", "no collision object could be imported"),
    ("world: {collision_objects: []}\n---\nworld: {collision_objects: []}\n---\n", "2 YAML documents separated by '---'; give one"),
])
def test_what_is_not_a_planning_scene_is_said_in_one_line(text, words, tmp_path):
    src = tmp_path / "in.yaml"
    src.write_text(text)
    with pytest.raises(SceneError) as info:
        _import(src, tmp_path, name="out")
    assert words in str(info.value) and "\n" not in str(info.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.yaml"]  # nothing left behind


@pytest.mark.parametrize("text, problem", [
    ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 2]}], primitive_poses: [{position: [0, 0, 0]}]}]}", "positive dimension"),
    ("world: {collision_objects: [{id: A, header: {frame_id: odom_x}, primitives: [], primitive_poses: []}]}", "frame_id"),
    ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: []}]}", "equal length"),
    ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: [{orientation: [0, 0, 0, 0]}]}]}", "zero quaternion"),
    ("world: {collision_objects: [{primitives: []}]}", "non-empty id"),
    ("robot_state: {joint_state: {name: [a, b], position: [1]}}", "equal length"),
    ("world: {collision_objects: [{id: A, header: 3, primitives: [], primitive_poses: []}]}", "header: expected a mapping"),
    ("world: {collision_objects: [{id: A, primitives: [3], primitive_poses: [3]}]}", "primitives[0]: expected a mapping"),
    ("world: {collision_objects: [{id: A, pose: 3, primitives: [], primitive_poses: []}]}", "pose: expected a mapping"),
    ("world: {collision_objects: [3]}", "world.collision_objects[0]: expected a mapping with a non-empty id"),
    ("robot_state: {joint_state: {name: [torso_lift_joint], position: [0.9]}}\nworld: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: [{position: [3, 0, 0]}]}]}", "outside its limits [0, 0.38615]"),
])
def test_bad_input_is_one_line_naming_the_object(text, problem, tmp_path):
    src = tmp_path / "bad.yml"
    src.write_text(text)
    (tmp_path / "out.yaml").write_text("# an older scene the failed import must not touch\n")
    with pytest.raises(SceneError) as info:
        _import(src, tmp_path, name="out")
    message = str(info.value)
    assert problem in message and "\n" not in message
    if "id: A" in text and "robot_state" not in text:
        assert "collision object 'A'" in message  # the source object, not an index
    assert (tmp_path / "out.yaml").read_text().startswith("# an older scene")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.yml", "out.yaml"]


def test_noisy_start_is_clamped_with_a_warning(tmp_path):
    result = _import(CORPUS / "noisy_small_shelves.yaml", tmp_path)
    scene = load_scene(result.output)
    assert scene.robot.start["torso_lift_joint"] == 0.0
    assert any("torso_lift_joint = -1.5e-08" in w and "clamped" in w for w in result.summary.warnings)


def test_start_options(tmp_path):
    src = CORPUS / "can_in_open_box.yaml"
    request = CORPUS / "can_in_open_box_request.yaml"
    result = _import(src, tmp_path, ImportOptions(start=StartOptions(request=str(request), joints="wrist_roll_joint=0.5")))
    start = load_scene(result.output).robot.start
    assert start["torso_lift_joint"] == 0.1 and start["wrist_roll_joint"] == 0.5
    assert result.summary.start_source == "motion-plan request can_in_open_box_request.yaml with --start-joints"
    result = _import(src, tmp_path, ImportOptions(start=StartOptions(name="tucked")))
    assert load_scene(result.output).robot.start["elbow_flex_joint"] == 1.72 and "named pose 'tucked'" in result.summary.line()
    for options, words in [
        (StartOptions(name="home"), "no named pose 'home' (named: tucked, zero)"),
        (StartOptions(name="tucked", request=str(request)), "give one of them"),
        (StartOptions(request=str(src)), "this is a MoveIt planning scene"),
        (StartOptions(joints="elbow=1"), "elbow is not a planned joint"),
        (StartOptions(joints="elbow_flex_joint"), "name=value"),
    ]:
        with pytest.raises(SceneError, match=words.replace("(", r"\(").replace(")", r"\)")):
            _import(src, tmp_path, ImportOptions(start=options), name="bad")
    assert not (tmp_path / "bad.yaml").exists()


def test_meshes_found_through_packages_and_relative_paths(tmp_path):
    result = _import(CORPUS / "kitchen_meshes.yaml", tmp_path, KITCHEN)
    scene = load_scene(result.output)
    meshes = {o.id: o.geometry.mesh for o in scene.obstacles if o.geometry.mesh}
    assert set(meshes) == {"counter_front", "counter_left", "fridge"}
    assert meshes["fridge"].file.endswith("meshes/fridge.stl") and Path(meshes["fridge"].file).is_file()
    warnings = [w for w in result.summary.warnings if "mesh" in w]
    assert len(warnings) == 1 and "2 of 7 collision objects (29%) dropped" in warnings[0]
    assert "oven" in warnings[0] and "wall_cabinet" in warnings[0]
    line = result.summary.line()
    assert "meshes: 3 imported, 2 dropped" in line and "can 2" in line and "start: the scene's robot_state" in line
    without = _import(CORPUS / "kitchen_meshes.yaml", tmp_path, name="bare")  # no --package: the counters go too
    assert without.summary.meshes_imported == 1 and "--package kitchen_description=DIR" in without.summary.warnings[-1]


def test_mesh_paths_inside_the_output_folder_are_relative(tmp_path):
    (tmp_path / "m").mkdir()
    (tmp_path / "m" / "block.obj").write_text((CORPUS / "kitchen_description" / "meshes" / "counter.obj").read_text())
    src = tmp_path / "s.yml"
    src.write_text("world:\n  collision_objects:\n    - id: block\n      meshes: [{resource: m/block.obj}]\n"
                   "      mesh_poses: [{position: [2, 0, 0]}]\n")
    out = _import(src, tmp_path).output
    assert yaml.safe_load(out.read_text())["obstacles"][0]["geometry"]["mesh"]["file"] == "m/block.obj"
    assert load_scene(out).obstacles[0].geometry.mesh.file == str((tmp_path / "m" / "block.obj").resolve())


def test_a_rule_naming_an_unknown_type_fails_at_import(tmp_path):
    options = ImportOptions(user_rules=(parse_rule("can_3=plant"),))
    with pytest.raises(SceneError, match="object 'can_3': unknown type 'plant'; .*from a --type or --rules rule"):
        _import(CORPUS / "bookshelf_cans.yaml", tmp_path, options)
    assert list(tmp_path.iterdir()) == []


def test_srdf_option_is_written_into_the_robot_block(tmp_path):
    from lazyground.cli import main

    srdf = tmp_path / "fetch.srdf"
    srdf.write_text('<robot name="fetch"><disable_collisions link1="base_link" link2="torso_lift_link" reason="Adjacent"/></robot>')
    source = tmp_path / "scene.yaml"
    source.write_text(ONE_WALL)
    out = tmp_path / "out.yaml"
    assert main(["import-moveit", str(source), "-o", str(out), "--srdf", str(srdf)]) == 0
    assert yaml.safe_load(out.read_text())["robot"]["srdf"] == str(srdf.resolve())


def test_a_topic_echo_ending_in_a_document_separator_imports(tmp_path):
    # audit8: a message saved with `ros2 topic echo --once` ends in '---': "YAML syntax error at line 82: but found
    # another document"
    src = tmp_path / "echo.yaml"
    src.write_text((CORPUS / "big_box_table.yaml").read_text() + "---\n")
    _import(src, tmp_path, name="out")
    assert (tmp_path / "out.yaml").is_file()


@pytest.mark.parametrize("text, this_is", [
    ("name: x\nrobot: {model: fetch}\n", "this is not one"),  # audit8: was "this is not a MoveIt planning scene"
    ("world: {collision_objects: []}\n", "this is a MoveIt planning scene"),
])
def test_start_from_says_what_the_file_is(text, this_is, tmp_path):
    from lazyground.moveit.start import request_start

    path = tmp_path / "r.yaml"
    path.write_text(text)
    with pytest.raises(SceneError, match=f"--start-from expects a MoveIt motion-plan request \\(start_state.joint_state\\); {this_is}$"):
        request_start(path)
