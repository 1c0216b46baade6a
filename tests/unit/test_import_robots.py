"""``import-moveit --robot panda|ur5e|PATH [--srdf S]``: the robot block comes from the robot's robot.yaml."""

from pathlib import Path

import pytest
import yaml

from lazyground.cli import main
from lazyground.scene import load_scene

REPO = Path(__file__).resolve().parents[2]
MOVEIT_SCENE = """\
name: t
world:
  collision_objects:
  - id: Can1
    header: {frame_id: world}
    primitives: [{type: 3, dimensions: [0.12, 0.033]}]
    primitive_poses: [{position: {x: 0.5, y: 0.0, z: 0.06}, orientation: {x: 0, y: 0, z: 0, w: 1}}]
"""


@pytest.mark.parametrize("robot,joint,value", [("panda", "panda_joint4", -2.356194), ("ur5e", "elbow_joint", 1.570796),
                                               (str(REPO / "models" / "panda" / "panda.urdf"), "panda_joint4", -2.356194)])
def test_arms_import_with_their_defaults(tmp_path, capsys, robot, joint, value):
    (tmp_path / "scene.yml").write_text(MOVEIT_SCENE)
    out = tmp_path / "out.yaml"
    assert main(["import-moveit", str(tmp_path / "scene.yml"), "--robot", robot, "-o", str(out)]) == 0
    scene = load_scene(out)
    assert scene.robot.start[joint] == pytest.approx(value)  # no joint state: the robot.yaml's start pose
    assert [o.id for o in scene.objects] == ["Can1"]


def test_srdf_goes_into_the_robot_block_and_unknown_robots_are_one_line(tmp_path, capsys):
    (tmp_path / "scene.yml").write_text(MOVEIT_SCENE)
    srdf = tmp_path / "panda.srdf"
    srdf.write_text("<robot name='panda'><group_state name='low' group='arm'><joint name='panda_joint2' value='0.3'/></group_state>"
                    "<disable_collisions link1='panda_link0' link2='panda_link2' reason='Never'/></robot>")
    out = tmp_path / "out.yaml"
    assert main(["import-moveit", str(tmp_path / "scene.yml"), "--robot", "panda", "--srdf", str(srdf), "-o", str(out)]) == 0
    assert yaml.safe_load(out.read_text())["robot"]["srdf"] == str(srdf)
    assert load_scene(out).robot.srdf == str(srdf)
    capsys.readouterr()
    assert main(["import-moveit", str(tmp_path / "scene.yml"), "--robot", "kuka", "-o", str(tmp_path / "k.yaml")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "unknown robot 'kuka': no robot model with a robot.yaml" in err
