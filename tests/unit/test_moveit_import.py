"""MoveIt planning-scene import (lazyground.moveit): the paper's scenes and malformed input."""

import math
import textwrap
from pathlib import Path

import pytest

from lazyground.moveit import TYPE_RULES, convert_moveit, import_moveit_file, object_type
from lazyground.scene import load_scene
from lazyground.scene.typed_yaml import SceneError

REFERENCE = Path(__file__).resolve().parents[2].parent / "shared" / "reference" / "moveit_scenes"
REFERENCE_FILES = sorted(REFERENCE.glob("*.yml")) if REFERENCE.is_dir() else []


@pytest.mark.skipif(not REFERENCE_FILES, reason="reference MoveIt scenes not available")
@pytest.mark.parametrize("path", REFERENCE_FILES, ids=lambda p: p.stem)
def test_reference_scene_converts_and_loads(path, tmp_path):
    out = tmp_path / "scene.yaml"
    warnings = import_moveit_file(path, "fetch", out)
    scene = load_scene(out)
    assert scene.robot.start["shoulder_pan_joint"] == pytest.approx(1.32)
    assert scene.robot.start["torso_lift_joint"] == pytest.approx(0.05)
    assert scene.robot.end_effector == "gripper_link"
    assert scene.planner.collision_padding < 0.01
    cans = scene.objects_of_type("can")
    assert cans and all(c.geometry.cylinder is not None for c in cans)
    assert scene.objects_of_type("shelf")
    if "scenario3" in path.stem:
        assert len(scene.objects_of_type("box")) == 5  # Cube1..5
        bar = next(o for o in scene.obstacles if o.id == "Bar1")
        assert bar.pose.rpy[1] == pytest.approx(1.0826348, abs=1e-6)
        assert sum("Bar" in w and "normalised" in w for w in warnings) == 2
    else:
        assert any(w.startswith("table_right:") and "mesh" in w for w in warnings)
        assert "table_right" not in {o.id for o in scene.objects + scene.obstacles}
        can1 = scene.object("Can1")  # MoveIt cylinder dimensions are [height, radius]
        assert can1.geometry.cylinder.length == pytest.approx(0.115)
        assert can1.geometry.cylinder.radius in (pytest.approx(0.035), pytest.approx(0.0325))


def _yaml(text: str) -> dict:
    import yaml

    return yaml.safe_load(textwrap.dedent(text))


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
          primitives: [{type: 1, dimensions: [0.3, 0.2, 0.1]}, {type: sphere, dimensions: [0.05]}]
          primitive_poses:
            - {position: [0.5, 0, 0.05], orientation: [0, 0, 0, 1]}
            - {position: [0.5, 0, 0.2], orientation: [0, 0, 0, 2]}
"""


def test_small_scene_poses_types_and_start(tmp_path):
    scene, warnings = convert_moveit(_yaml(SMALL), "fetch", "small.yml", rules=(("Crate", "box"),) + TYPE_RULES)
    mug = next(o for o in scene["objects"] if o["id"] == "Mug7")
    assert mug["type"] == "cup"
    assert mug["pose"]["xyz"] == pytest.approx([1.0, 0.5, 0.8])  # object pose composed with the primitive pose
    assert mug["pose"]["rpy"][2] == pytest.approx(math.pi / 2)
    assert mug["geometry"] == {"cylinder": {"radius": 0.04, "length": 0.1}}
    crates = [o for o in scene["objects"] if o["id"].startswith("Crate")]
    assert [c["id"] for c in crates] == ["Crate_1", "Crate_2"] and all(c["type"] == "box" for c in crates)
    assert crates[1]["geometry"] == {"sphere": {"radius": 0.05}}
    assert any("Crate_2" in w and "norm 2.000000" in w for w in warnings)
    assert scene["robot"]["start"]["torso_lift_joint"] == 0.2
    assert scene["robot"]["start"]["wrist_flex_joint"] == 1.66  # missing joints: the default pose, with a warning
    assert any("wrist_flex_joint" in w for w in warnings)


def test_type_rules_are_prefixes_and_default_to_obstacle():
    assert object_type("Can12") == "can"
    assert object_type("cube_a") == "box"
    assert object_type("Shelf2_3") == "shelf"
    assert object_type("Bar1") == "obstacle"
    assert object_type("Plant") == "obstacle"
    assert object_type("Plant", rules=(("Pl", "plant"),)) == "plant"


@pytest.mark.parametrize(
    "text,problem",
    [
        ("[1, 2]", "mapping"),
        ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 2]}], primitive_poses: [{position: [0, 0, 0]}]}]}", "positive dimension"),
        ("world: {collision_objects: [{id: A, header: {frame_id: odom_x}, primitives: [], primitive_poses: []}]}", "frame_id"),
        ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: []}]}", "equal length"),
        ("world: {collision_objects: [{id: A, primitives: [{type: box, dimensions: [1, 1, 1]}], primitive_poses: [{orientation: [0, 0, 0, 0]}]}]}", "zero quaternion"),
        ("world: {collision_objects: [{primitives: []}]}", "non-empty id"),
        ("robot_state: {joint_state: {name: [a, b], position: [1]}}", "equal length"),
    ],
)
def test_bad_input_is_one_line_scene_error(text, problem):
    with pytest.raises(SceneError) as info:
        convert_moveit(_yaml(text), "fetch", "bad.yml")
    assert problem in str(info.value) and "\n" not in str(info.value)


def test_unknown_robot_and_missing_file(tmp_path):
    with pytest.raises(SceneError, match="unknown robot"):
        convert_moveit({}, "pr2", "x.yml")
    with pytest.raises(SceneError, match="cannot read"):
        import_moveit_file(tmp_path / "missing.yml", "fetch", tmp_path / "out.yaml")


def test_meshes_are_skipped_with_a_warning(tmp_path):
    src = tmp_path / "m.yml"
    src.write_text("world:\n  collision_objects:\n    - id: Table9\n      meshes: [{resource: package://x/t.dae}]\n      mesh_poses: [{position: [0, 0, 0]}]\n")
    out = tmp_path / "m.yaml"
    warnings = import_moveit_file(src, "fetch", out)
    assert "Table9: 1 mesh skipped (meshes are not supported; model it from primitives)" in warnings
    assert load_scene(out).objects == ()
