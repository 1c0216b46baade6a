"""Robot descriptions without pydrake: package:// resolution, STL to OBJ, SRDF reading, and the
scene's robot block completed from robot.yaml / SRDF (named-pose starts, from + overrides)."""

from __future__ import annotations

import struct
import textwrap
from pathlib import Path

import numpy as np
import pytest

from lazyground.mesh_files import read_stl
from lazyground.robots.description import discover_packages, obj_for, parse_package_args, prepare_model, resolve_uri
from lazyground.robots.srdf import read_srdf
from lazyground.scene import SceneError, parse_scene

TRIANGLE = np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 1, 0], [0, 0, 1]]], float)


def _binary_stl(path: Path, tris) -> None:
    with open(path, "wb") as f:
        f.write(b"solid but actually binary".ljust(80, b" "))  # a binary header may start with "solid"
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<12f", 0, 0, 0, *np.ravel(t)) + b"\0\0")


def _ascii_stl(path: Path, tris) -> None:
    body = "".join("facet normal 0 0 0\n outer loop\n" + "".join(f"  vertex {x} {y} {z}\n" for x, y, z in t) + " endloop\nendfacet\n" for t in tris)
    path.write_text(f"solid t\n{body}endsolid t\n")


def _package(root: Path, name: str) -> Path:
    folder = root / name
    (folder / "meshes").mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)


@pytest.mark.parametrize("writer", [_binary_stl, _ascii_stl])
def test_stl_converts_to_an_obj_with_the_same_triangles(tmp_path, writer):
    stl = tmp_path / "part.STL"
    writer(stl, TRIANGLE)
    vertices, triangles = read_stl(stl)
    np.testing.assert_allclose(vertices[triangles], TRIANGLE)
    obj = obj_for(stl)
    assert obj.suffix == ".obj" and obj.parent == tmp_path / "cache" / "meshes"
    lines = obj.read_text().splitlines()
    vertices = np.array([[float(v) for v in line.split()[1:]] for line in lines if line.startswith("v ")])
    faces = np.array([[int(v) for v in line.split()[1:]] for line in lines if line.startswith("f ")])
    np.testing.assert_allclose(vertices[faces - 1], TRIANGLE)
    assert obj_for(stl) == obj  # cached by content


def test_an_unwritable_mesh_cache_is_one_line_naming_the_fix(tmp_path, monkeypatch):
    # audit8: HOME=/proc (a read-only home in a container) was "internal error: FileNotFoundError: ... '/proc/.cache'"
    stl = tmp_path / "part.stl"
    _binary_stl(stl, TRIANGLE)
    (tmp_path / "file").write_text("")
    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "file"))  # a file where the cache folder should be
    with pytest.raises(SceneError, match=r"part\.stl: cannot write the converted mesh to .*/file/meshes: .*; "
                                         r"set LAZYGROUND_CACHE to a writable folder$"):
        obj_for(stl)


def test_not_an_stl_and_unknown_formats_are_one_line(tmp_path):
    bad = tmp_path / "bad.stl"
    bad.write_bytes(b"\x00\x01 garbage")
    with pytest.raises(SceneError, match=r"not an STL file .*; convert it to OBJ"):
        obj_for(bad)
    ply = tmp_path / "part.ply"
    ply.write_text("ply")
    with pytest.raises(SceneError, match=r"mesh format \.ply is not supported .* convert it to OBJ"):
        obj_for(ply)
    obj = tmp_path / "part.obj"
    obj.write_text("v 0 0 0\n")
    assert obj_for(obj) == obj  # Drake reads OBJ itself


def test_package_uris_resolve_through_given_own_and_ros_path_packages(tmp_path, monkeypatch):
    own = _package(tmp_path / "ws", "arm_description")
    sibling = _package(tmp_path / "ws", "arm_meshes")
    elsewhere = _package(tmp_path / "other", "gripper_description")
    model = own / "robot.urdf"
    model.write_text("<robot name='r'/>")
    assert discover_packages(model, env={}) == {"arm_description": own, "arm_meshes": sibling}
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "other"))
    assert discover_packages(model)["gripper_description"] == elsewhere
    (elsewhere / "meshes" / "f.obj").write_text("v 0 0 0\n")
    assert resolve_uri("package://gripper_description/meshes/f.obj", own, discover_packages(model), model) == elsewhere / "meshes" / "f.obj"
    with pytest.raises(SceneError, match=r"unknown package 'nope' \(known: arm_description, arm_meshes\); give its folder with "
                                         r"robot.packages: \{nope: DIR\} in the scene, --package nope=DIR, or ROS_PACKAGE_PATH"):
        resolve_uri("package://nope/x.stl", own, discover_packages(model, env={}), model)
    assert parse_package_args([f"a={own}", f"b={sibling}"]) == {"a": own.resolve(), "b": sibling.resolve()}
    with pytest.raises(SceneError, match="expected NAME=DIR"):
        parse_package_args(["just_a_name"])
    with pytest.raises(SceneError, match="is not a folder"):
        parse_package_args([f"a={tmp_path / 'nowhere'}"])


def test_prepare_model_rewrites_meshes_and_keeps_drake_tags(tmp_path):
    pkg = _package(tmp_path, "arm_description")
    _binary_stl(pkg / "meshes" / "link.stl", TRIANGLE)
    (pkg / "meshes" / "hand.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    urdf = pkg / "arm.urdf"
    urdf.write_text(textwrap.dedent("""\
        <robot name="arm" xmlns:drake="http://drake.mit.edu">
          <link name="a"><collision><geometry><mesh filename="package://arm_description/meshes/link.stl"/></geometry></collision>
            <visual><geometry><mesh filename="meshes/hand.obj"/></geometry></visual></link>
          <drake:collision_filter_group name="g"><drake:member link="a"/></drake:collision_filter_group>
        </robot>"""))
    prepared = prepare_model(urdf)
    assert prepared.file_type == "urdf" and prepared.converted == ("package://arm_description/meshes/link.stl",)
    assert prepared.packages == {"arm_description": str(pkg)}
    assert "package://" not in prepared.text and "drake:collision_filter_group" in prepared.text
    assert f'filename="file://{pkg / "meshes" / "hand.obj"}"' in prepared.text


def test_srdf_pairs_states_and_what_is_not_used(tmp_path):
    srdf = tmp_path / "r.srdf"
    srdf.write_text(textwrap.dedent("""\
        <robot name="r">
          <group name="arm"><chain base_link="a" tip_link="b"/></group>
          <group_state name="home" group="arm"><joint name="j1" value="0.5"/><joint name="j2" value="-1"/></group_state>
          <group_state name="home" group="gripper"><joint name="finger" value="0.04"/></group_state>
          <disable_collisions link1="a" link2="b" reason="Adjacent"/>
        </robot>"""))
    parsed = read_srdf(srdf)
    assert parsed.disabled_collisions == (("a", "b"),)
    assert parsed.named_poses == {"home": {"j1": 0.5, "j2": -1.0, "finger": 0.04}}  # one state over two groups
    assert parsed.ignored == {"group": 1}
    (tmp_path / "bad.srdf").write_text("<robot><disable_collisions link1='a'/></robot>")
    with pytest.raises(SceneError, match="<disable_collisions> without a 'link2' attribute"):
        read_srdf(tmp_path / "bad.srdf")
    (tmp_path / "urdf.srdf").write_text("<package/>")
    with pytest.raises(SceneError, match="not an SRDF file"):
        read_srdf(tmp_path / "urdf.srdf")


REPO = Path(__file__).resolve().parents[2]


def _robot(start_yaml: str, extra: str = "") -> dict:
    text = f"name: t\nrobot:\n  model: panda\n  base: {{xyz: [0, 0, 0]}}\n{start_yaml}{extra}"
    return parse_scene(text, "s.yaml", REPO).robot


def test_start_named_from_overrides_or_left_to_the_robot():
    ready = {"panda_joint1": 0.0, "panda_joint2": -0.785398, "panda_joint3": 0.0, "panda_joint4": -2.356194,
             "panda_joint5": 0.0, "panda_joint6": 1.570796, "panda_joint7": 0.785398}
    assert _robot("").start == ready  # robot.yaml's start: ready
    assert _robot("  start: transport\n").start["panda_joint4"] == -2.9
    assert _robot("  start: {from: ready, panda_joint1: 0.3}\n").start == {**ready, "panda_joint1": 0.3}
    robot = _robot("")
    assert robot.base_link == "panda_link0" and robot.planned_joints[0] == "panda_joint1"
    assert robot.end_effector.frame == "panda_hand_tcp" and robot.end_effector.approach_axis == "z"
    with pytest.raises(SceneError, match=r"^s.yaml: robot.start: no named pose 'tucked' \(named: ready, transport\)"):
        _robot("  start: tucked\n")
    with pytest.raises(SceneError, match=r"robot.start.panda_joint1: expected a number"):
        _robot("  start: {from: ready, panda_joint1: fast}\n")


def test_srdf_states_are_named_poses_and_paths_resolve_against_the_scene(tmp_path):
    (tmp_path / "p.srdf").write_text("<robot name='panda'><group_state name='up' group='arm'>"
                                     "<joint name='panda_joint2' value='0.1'/></group_state></robot>")
    text = ("name: t\nrobot: {model: panda, base: {xyz: [0, 0, 0]}, srdf: p.srdf, start: {from: up},"
            " packages: {franka_description: ../fd}, allowed_collisions: [[panda_link0, panda_link2]]}\n")
    robot = parse_scene(text, "s.yaml", tmp_path).robot
    assert robot.start == {"panda_joint2": 0.1}
    assert robot.srdf == str(tmp_path / "p.srdf") and robot.packages == {"franka_description": str((tmp_path / "../fd").resolve())}
    assert robot.allowed_collisions == (("panda_link0", "panda_link2"),)
    with pytest.raises(SceneError, match=r"robot.srdf: file .*missing.srdf not found"):
        parse_scene(text.replace("p.srdf", "missing.srdf"), "s.yaml", tmp_path)


def test_end_effector_mapping_in_a_scene():
    robot = _robot("", "  end_effector: {frame: panda_link8, approach_axis: z, closing_axis: x, opening: 0.05, offset_xyz: [0, 0, 0.2]}\n")
    assert (robot.end_effector.frame, robot.end_effector.closing_axis, robot.end_effector.offset_xyz) == ("panda_link8", "x", (0.0, 0.0, 0.2))
    with pytest.raises(SceneError, match="closing_axis: must differ from approach_axis"):
        _robot("", "  end_effector: {frame: panda_link8, approach_axis: z, closing_axis: -z}\n")


def test_dae_converts_through_trimesh_when_installed(tmp_path):
    trimesh = pytest.importorskip("trimesh")
    pytest.importorskip("collada")
    dae = tmp_path / "box.dae"
    dae.write_bytes(trimesh.exchange.dae.export_collada(trimesh.creation.box(extents=(0.1, 0.2, 0.3))))
    lines = obj_for(dae).read_text().splitlines()
    vertices = np.array([[float(v) for v in line.split()[1:]] for line in lines if line.startswith("v ")])
    np.testing.assert_allclose(vertices.max(axis=0) - vertices.min(axis=0), [0.1, 0.2, 0.3], atol=1e-9)
    assert sum(line.startswith("f ") for line in lines) == 12


def test_sdf_mesh_uris_resolve_and_other_uris_stay(tmp_path):
    pkg = _package(tmp_path, "arm_description")
    _ascii_stl(pkg / "meshes" / "link.stl", TRIANGLE)
    sdf = pkg / "arm.sdf"
    sdf.write_text(textwrap.dedent("""\
        <sdf version="1.9"><model name="arm"><link name="a">
          <collision name="c"><geometry><mesh><uri>package://arm_description/meshes/link.stl</uri></mesh></geometry></collision>
          <visual name="v"><geometry><box><size>1 1 1</size></box></geometry>
            <material><script><uri>file://media/materials/scripts</uri></script></material></visual>
        </link></model></sdf>"""))
    prepared = prepare_model(sdf)
    assert prepared.file_type == "sdf" and list(prepared.meshes) == ["package://arm_description/meshes/link.stl"]
    assert "file://media/materials/scripts" in prepared.text and "package://" not in prepared.text


def test_an_absolute_path_into_another_machines_install_space_reads_the_known_package(tmp_path):
    # kortex_description's gen3_2f85.urdf names file:///root/<ws>/install/kortex_description/share/kortex_description/...
    pkg = tmp_path / "kortex_description"
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "meshes" / "a.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    uri = "file:///root/ws/install/kortex_description/share/kortex_description/meshes/a.obj"
    assert resolve_uri(uri, tmp_path, {"kortex_description": pkg}, tmp_path / "m.urdf") == (pkg / "meshes" / "a.obj").resolve()
    with pytest.raises(SceneError, match="not found"):
        resolve_uri(uri, tmp_path, {}, tmp_path / "m.urdf")
