"""Reading descriptions no stricter than Drake (#28): undeclared prefixes, tags planning does not use, continuous limits."""

import xml.etree.ElementTree as ET

import pytest

from lazyground.robots.description import prepare_model
from lazyground.robots.lenient_xml import drop_world_weld, parse_lenient, strip_unused, unwrap_continuous_limits
from lazyground.robots.xacro_file import parse_xacro_arg, xacro_value
from lazyground.typed_yaml import SceneError

URDF = """<robot name="r"><link name="world"/><link name="base_link"/><link name="a"/>
<joint name="fix" type="fixed"><parent link="world"/><child link="base_link"/></joint>
<joint name="j" type="continuous"><parent link="base_link"/><child link="a"/><limit lower="-174.5" upper="174.5" effort="1" velocity="1"/>
<safety_controller k_velocity="1"/></joint>
<transmission name="t"/><transmission name="t"/><gazebo/><ros2_control name="x"/></robot>"""


def test_an_undeclared_drake_prefix_is_read_as_drake_reads_it():
    with pytest.raises(ET.ParseError):
        ET.fromstring('<sdf><model name="m"><drake:joint name="x"/></model></sdf>')
    root = parse_lenient('<sdf><model name="m"><drake:joint name="x"/><link drake:foo="1"/></model></sdf>')
    assert root.find("model")[0].tag == "{http://drake.mit.edu}joint"


def test_tags_planning_does_not_use_are_stripped_and_continuous_limits_dropped():
    root = ET.fromstring(URDF)
    assert strip_unused(root) == {"transmission": 2, "gazebo": 1, "ros2_control": 1, "safety_controller": 1}
    notes = unwrap_continuous_limits(root)
    assert notes == ["continuous joints wrap (their URDF position limits are ignored): j [-174.5, 174.5]"]
    assert root.find("joint[@name='j']/limit").get("lower") is None


def test_the_models_weld_to_world_gives_way_to_robot_base():
    root = ET.fromstring(URDF)
    assert "'fix' from world to base_link" in drop_world_weld(root, "base_link")
    assert root.find("joint[@name='fix']") is None and root.find("link[@name='world']") is None
    assert drop_world_weld(ET.fromstring(URDF), "a") is None


def test_prepare_model_reads_an_sdf_with_undeclared_drake_tags(tmp_path):
    sdf = tmp_path / "m.sdf"
    sdf.write_text('<?xml version="1.0"?><sdf version="1.9"><model name="m"><link name="l"/>'
                   '<drake:collision_filter_group name="g"><drake:member>l</drake:member></drake:collision_filter_group></model></sdf>')
    prepared = prepare_model(sdf)
    assert prepared.file_type == "sdf" and "drake:collision_filter_group" in prepared.text


def test_xacro_args_as_the_cli_and_scenes_give_them():
    assert parse_xacro_arg("ur_type:=ur5e") == ("ur_type", "ur5e") and parse_xacro_arg("a=b=c") == ("a", "b=c")
    with pytest.raises(SceneError, match="expected NAME=VALUE"):
        parse_xacro_arg("ur5e")
    assert [xacro_value(v) for v in (True, 7.0, 0.5, "x")] == ["true", "7", "0.5", "x"]
