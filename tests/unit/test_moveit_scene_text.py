"""Issue 34: MoveIt's text ``.scene`` format (RViz's Scene Objects export, ``PlanningScene::saveGeometryToStream``)
imports like a YAML planning scene: both layouts, boxes, cylinders, spheres, cones, inline meshes (written as OBJ
files beside the output), the same typing rules and summary; malformed text is one line, nothing left behind."""

from __future__ import annotations

import pytest

from lazyground.moveit import ImportOptions, import_moveit_file
from lazyground.moveit.scene_text import parse_scene_text
from lazyground.scene import load_scene
from lazyground.typed_yaml import SceneError

# MoveIt 2 / Noetic layout: an object pose, and subframes after the shapes
NEW = """\
kitchen
* table_top
1.0 0 0.7
0 0 0 1
1
box
1.2 0.8 0.04
0 0 0
0 0 0 1
0.55 0.35 0.2 1
0
* Can1
0.9 0.1 0.78
0 0 0.7071068 0.7071068
1
cylinder
0.033 0.12
0 0 0
0 0 0 1
0 0 0 0
0
* funnel
0.7 -0.3 0.8
0 0 0 1
1
cone
0.05 0.1
0 0 0
0 0 0 1
0 0 0 0
1
tip
0 0 0.05
0 0 0 1
* wedge
0.7 0.3 0.75
0 0 0 1
1
mesh
4 4
0 0 0
0.1 0 0
0 0.1 0
0 0 0.1
0 1 2
0 1 3
0 2 3
1 2 3
0 0 0
0 0 0 1
0 0 0 0
0
.
"""
# the older layout: no object pose, no subframes (and, in the oldest files, no colour line)
OLD = """\
(noname)+
* box_1
1
box
0.1 0.1 0.1
0.5 0 0.5
0 0 0 1
0 0 0 0
* ball
2
sphere
0.05
0.5 0.4 0.5
0 0 0 1
sphere
0.05
0.5 0.5 0.5
0 0 0 1
.
"""


def _import(text: str, tmp_path, name="scene.scene"):
    src = tmp_path / name
    src.write_text(text)
    return import_moveit_file(src, tmp_path / "out.yaml", ImportOptions(), check_start=False)


def test_the_moveit2_layout_imports_every_shape(tmp_path):
    result = _import(NEW, tmp_path)
    scene = load_scene(result.output)
    objects = {o.id: o for o in scene.objects}
    obstacles = {o.id: o for o in scene.obstacles}
    assert objects["table_top"].type == "table" and objects["Can1"].type == "can"  # the YAML import's typing rules
    can = objects["Can1"]
    assert (can.geometry.cylinder.radius, can.geometry.cylinder.length) == (0.033, 0.12)  # radius, length in the text
    assert can.pose.xyz == pytest.approx((0.9, 0.1, 0.78)) and can.pose.rpy[2] == pytest.approx(1.5707963, abs=1e-6)
    assert obstacles["funnel"].geometry.cylinder.radius == 0.05  # a cone: its bounding cylinder
    mesh = obstacles["wedge"].geometry.mesh
    assert mesh.file.endswith("out_meshes/wedge_0.obj")
    obj = (tmp_path / "out_meshes" / "wedge_0.obj").read_text().splitlines()
    assert sum(line.startswith("v ") for line in obj) == 4 and "f 1 2 3" in obj
    summary = result.summary.line()
    assert "4 collision objects" in summary and "meshes: 1 imported, 0 dropped" in summary
    assert any("cone" in w for w in result.summary.warnings)


def test_the_older_layout_has_no_object_pose(tmp_path):
    data = parse_scene_text(OLD, "old.scene")
    box, ball = data["world"]["collision_objects"]
    assert "pose" not in box and box["primitive_poses"][0]["position"] == {"x": 0.5, "y": 0.0, "z": 0.5}
    assert [p["type"] for p in ball["primitives"]] == ["sphere", "sphere"]  # no colour lines: the oldest files
    scene = load_scene(_import(OLD, tmp_path).output)
    assert sorted(o.id for o in scene.obstacles) == ["ball_1", "ball_2", "box_1"]


@pytest.mark.parametrize("text, words", [
    (NEW.replace("0.033 0.12", "0.033 x"), "line 17: object 'Can1': shape 1 (cylinder) dimensions: expected a number, got 'x'"),
    (NEW.replace("cone\n", "torus\n"), "object 'funnel': shape 1 (torus): unknown shape type"),
    (NEW[: NEW.index("* wedge")], "the file ends where"),
    (NEW.replace("1 2 3\n0 0 0\n", "1 2 9\n0 0 0\n"), "a triangle refers to a vertex beyond the 4 given"),
    ("x\n* \n1\n.\n", "an object without an id"),
])
def test_malformed_scene_text_is_one_line_and_leaves_nothing(text, words, tmp_path):
    with pytest.raises(SceneError) as info:
        _import(text, tmp_path)
    assert words in str(info.value) and "\n" not in str(info.value), str(info.value)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.scene"]
