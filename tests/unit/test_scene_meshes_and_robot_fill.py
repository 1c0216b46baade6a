"""Scene mesh geometry (OBJ/STL files, obstacles only) and robot keys/planner filled from robot.yaml (#15)."""

import struct
import textwrap

import numpy as np
import pytest

from lazyground.mesh_files import MeshFileError, obj_text, read_stl
from lazyground.moveit.start import StartOptions, override_scene_start
from lazyground.scene import load_scene
from lazyground.scene.loader import parse_scene
from lazyground.typed_yaml import SceneError

FETCH = "{model: fetch, base: {xyz: [0, 0, 0]}, start: {torso_lift_joint: 0.05, shoulder_pan_joint: 1.32, shoulder_lift_joint: 1.4, upperarm_roll_joint: -0.2, elbow_flex_joint: 1.72, forearm_roll_joint: 0.0, wrist_flex_joint: 1.66, wrist_roll_joint: 0.0}, planned_joints: [torso_lift_joint, shoulder_pan_joint, shoulder_lift_joint, upperarm_roll_joint, elbow_flex_joint, forearm_roll_joint, wrist_flex_joint, wrist_roll_joint]}"  # tucked
CUBE = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
TRIS = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                 [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])


def _binary_stl(vertices, triangles) -> bytes:
    out = b"x" * 80 + struct.pack("<I", len(triangles))
    for tri in triangles:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *vertices[i]) for i in tri) + b"\0\0"
    return out


def _ascii_stl(vertices, triangles) -> str:
    facets = "".join("facet normal 0 0 0\n outer loop\n" + "".join(f"  vertex {x} {y} {z}\n" for x, y, z in vertices[t])
                     + " endloop\nendfacet\n" for t in triangles)
    return f"solid cube\n{facets}endsolid cube\n"


@pytest.mark.parametrize("binary", [True, False])
def test_stl_reads_back_the_cube(tmp_path, binary):
    path = tmp_path / "c.stl"
    path.write_bytes(_binary_stl(CUBE, TRIS)) if binary else path.write_text(_ascii_stl(CUBE, TRIS))
    vertices, triangles = read_stl(path)
    assert len(vertices) == 8 and len(triangles) == 12  # shared corners merged
    assert np.allclose(np.sort(vertices[triangles].reshape(-1, 3), axis=0), np.sort(CUBE[TRIS].reshape(-1, 3), axis=0))
    assert obj_text(vertices, triangles).count("\nf ") == 12 and obj_text(vertices, triangles).count("v ") == 8


def test_not_an_stl(tmp_path):
    path = tmp_path / "c.stl"
    path.write_text("hello")
    with pytest.raises(MeshFileError, match="not an STL"):
        read_stl(path)


def _scene(tmp_path, body: str, name="s.yaml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(body).replace("robot: FETCH", f"robot: {FETCH}"))
    return path


def test_mesh_obstacles_load_relative_to_the_scene(tmp_path):
    (tmp_path / "block.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    path = _scene(tmp_path, """
        name: m
        robot: FETCH
        obstacles:
          - {id: block, geometry: {mesh: {file: block.obj, scale: [1, 2, 1]}}, pose: {xyz: [2, 0, 0]}}
    """)
    scene = load_scene(path)
    assert scene.obstacles[0].geometry.kind == "mesh"
    assert scene.obstacles[0].geometry.mesh.file == str((tmp_path / "block.obj").resolve())


@pytest.mark.parametrize("geometry, words", [
    ("{mesh: {file: missing.obj}}", "obstacles[0].geometry.mesh.file: 'block': no such file 'missing.obj'"),
    ("{mesh: {file: block.dae}}", "mesh files must be .obj or .stl"),
    ("{mesh: {file: block.obj, scale: [1, 0, 1]}}", "scale"),
])
def test_bad_mesh_obstacles(tmp_path, geometry, words):
    (tmp_path / "block.obj").write_text("v 0 0 0\n")
    path = _scene(tmp_path, f"""
        name: m
        robot: {FETCH}
        obstacles: [{{id: block, geometry: {geometry}}}]
    """)
    with pytest.raises(SceneError, match=words.replace("[", r"\[").replace("]", r"\]").replace(".", r"\.")):
        load_scene(path)


def test_a_mesh_cannot_be_a_typed_object(tmp_path):
    (tmp_path / "c.obj").write_text("v 0 0 0\n")
    path = _scene(tmp_path, f"""
        name: m
        robot: {FETCH}
        objects: [{{id: cup, type: cup, geometry: {{mesh: {{file: c.obj}}}}}}]
    """)
    with pytest.raises(SceneError, match="meshes can only be obstacles"):
        load_scene(path)


def test_robot_yaml_planner_layers_under_the_scene():
    bare = parse_scene("name: m\nrobot: {model: fetch, base: {xyz: [0, 0, 0]}, start: {torso_lift_joint: 0.1}}\n")
    assert bare.planner.algorithm == "bidirectional" and bare.planner.edge_resolution == 0.05  # the robot's
    assert bare.planner.per_algorithm["rrt"].step_size == 2.65
    own = parse_scene("name: m\nrobot: {model: fetch, base: {xyz: [0, 0, 0]}, start: {torso_lift_joint: 0.1}}\n"
                      "planner: {step_size: 0.3, per_algorithm: {bidirectional: {edge_resolution: 0.02}}}\n")
    p = own.planner  # robot.yaml < the scene's planner block, key by key
    assert p.algorithm == "bidirectional" and p.step_size == 0.3 and p.collision_padding == 0.005
    assert "rrt" not in p.per_algorithm  # the scene's step_size beats the robot's per-algorithm step
    assert p.per_algorithm["bidirectional"].edge_resolution == 0.02
    car = parse_scene("name: c\nrobot: {model: car, start: {car_x: 1, car_y: 1}, limits: {car_x: [0, 9], car_y: [0, 9]}}\n")
    assert car.planner.algorithm == "rrt"  # the car's robot.yaml has no planner block: the declared defaults


def test_plan_start_override_uses_the_shared_parser():
    scene = parse_scene("name: m\nrobot: {model: fetch, base: {xyz: [0, 0, 0]}, start: {torso_lift_joint: 0.05},\n"
                        "  planned_joints: [torso_lift_joint, elbow_flex_joint]}\n")
    same, warnings = override_scene_start(scene, StartOptions())
    assert same is scene and warnings == []
    zero, _ = override_scene_start(scene, StartOptions(name="zero", joints="torso_lift_joint=-5e-7"))
    assert zero.robot.start["elbow_flex_joint"] == 0.0 and zero.robot.start["torso_lift_joint"] == 0.0
    with pytest.raises(SceneError, match="outside its limits"):
        override_scene_start(scene, StartOptions(joints="torso_lift_joint=-0.01"))
