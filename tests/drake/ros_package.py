"""Build a robot description laid out as a ROS package, on the fly (issue #18's done-when test).

``make_package(root)`` writes ``root/my_arm_description/`` with a package.xml, a URDF whose
collision geometry is ``package://my_arm_description/meshes/*.stl`` (binary STL written by
numpy), an SRDF with disabled pairs and named states, and a z-forward tool frame. The arm is the
bundled UR5e's kinematics (models/ur5e) with every primitive written as an STL mesh of its
shape, the Drake-only collision filter groups dropped (a ROS package has none), and a
force-torque sensor link between the flange and the gripper that overlaps wrist_2_link: the start
pose is in collision unless the SRDF's disable_collisions pair is applied, as a MoveIt user has it.
"""

from __future__ import annotations

import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

UR5E = Path(__file__).resolve().parents[2] / "models" / "ur5e" / "ur5e.urdf"
PACKAGE = "my_arm_description"
# (a, b) corners of a unit cube's 12 triangles, outward-facing
_CUBE_FACES = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1),
               (2, 3, 7), (2, 7, 6), (0, 2, 6), (0, 6, 4), (1, 5, 7), (1, 7, 3)]


def write_box_stl(path: Path, size) -> None:
    """A box centred on its origin as a binary STL file."""
    corners = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]) * np.asarray(size, float)
    _write_stl(path, np.array([corners[list(face)] for face in _CUBE_FACES]))


def write_cylinder_stl(path: Path, radius: float, length: float, sides: int = 24) -> None:
    """A cylinder along z centred on its origin, as a binary STL prism (vertices on the circle)."""
    a = np.linspace(0, 2 * np.pi, sides, endpoint=False)
    ring = np.column_stack([radius * np.cos(a), radius * np.sin(a)])
    top, bottom = np.column_stack([ring, np.full(sides, length / 2)]), np.column_stack([ring, np.full(sides, -length / 2)])
    tris = []
    for i in range(sides):
        j = (i + 1) % sides
        tris += [(bottom[i], bottom[j], top[j]), (bottom[i], top[j], top[i]),
                 ((0, 0, length / 2), top[i], top[j]), ((0, 0, -length / 2), bottom[j], bottom[i])]
    _write_stl(path, np.array(tris, float))


def _write_stl(path: Path, triangles: np.ndarray) -> None:
    with open(path, "wb") as f:
        f.write(b"binary STL written by tests/drake/ros_package.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for tri in triangles:
            normal = np.cross(tri[1] - tri[0], tri[2] - tri[0])
            f.write(struct.pack("<3f", *(normal / np.linalg.norm(normal))))
            for v in tri:
                f.write(struct.pack("<3f", *v))
            f.write(b"\0\0")


def _write_shape_stl(path: Path, geometry: ET.Element) -> None:
    """The URDF primitive as an STL mesh of the same shape."""
    shape = geometry[0]
    if shape.tag == "box":
        write_box_stl(path, tuple(float(v) for v in shape.get("size").split()))
    else:
        write_cylinder_stl(path, float(shape.get("radius")), float(shape.get("length")))


SRDF = """<?xml version="1.0"?>
<robot name="my_arm">
  <group name="manipulator"><chain base_link="base_link" tip_link="tool_tcp"/></group>
  <group_state name="ready" group="manipulator">
    <joint name="shoulder_pan_joint" value="0"/><joint name="shoulder_lift_joint" value="-1.5708"/>
    <joint name="elbow_joint" value="1.5708"/><joint name="wrist_1_joint" value="-1.5708"/>
    <joint name="wrist_2_joint" value="-1.5708"/><joint name="wrist_3_joint" value="0"/>
  </group_state>
  <group_state name="folded" group="manipulator">
    <joint name="shoulder_pan_joint" value="0"/><joint name="shoulder_lift_joint" value="-1.5708"/>
    <joint name="elbow_joint" value="3.1"/><joint name="wrist_1_joint" value="0"/>
    <joint name="wrist_2_joint" value="0"/><joint name="wrist_3_joint" value="0"/>
  </group_state>
  <end_effector name="gripper" parent_link="tool0" group="manipulator"/>
  <disable_collisions link1="wrist_2_link" link2="fts_robotside" reason="Adjacent"/>
  <disable_collisions link1="wrist_3_link" link2="fts_robotside" reason="Adjacent"/>
  <disable_collisions link1="base_link_inertia" link2="shoulder_link" reason="Adjacent"/>
  <disable_collisions link1="robotiq_inner_knuckle" link2="fts_robotside" reason="Never"/>
</robot>
"""


def make_package(root: Path, mesh_uri: str = f"package://{PACKAGE}/meshes", srdf: str = SRDF) -> Path:
    """Write the package under ``root``; return its folder (see module docstring)."""
    pkg = root / PACKAGE
    (pkg / "meshes").mkdir(parents=True)
    (pkg / "urdf").mkdir()
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text(f'<?xml version="1.0"?>\n<package format="3"><name>{PACKAGE}</name><version>0.1.0</version>'
                                     '<description>test arm</description><maintainer email="a@b.c">a</maintainer>'
                                     '<license>BSD</license></package>\n')
    tree = ET.parse(UR5E)
    robot = tree.getroot()
    robot.set("name", "my_arm")
    for group in [e for e in robot if "collision_filter_group" in e.tag]:
        robot.remove(group)
    count = 0
    for link in robot.iter("link"):
        for role in ("collision", "visual"):
            for element in link.findall(role):
                geometry = element.find("geometry")
                name = f"part_{count}.stl"
                count += 1
                _write_shape_stl(pkg / "meshes" / name, geometry)
                geometry.clear()
                ET.SubElement(geometry, "mesh", filename=f"{mesh_uri}/{name}")
    # a force-torque sensor between the flange and the gripper, reaching back over wrist_2_link
    write_box_stl(pkg / "meshes" / "fts.stl", (0.09, 0.09, 0.05))
    sensor = ET.SubElement(robot, "link", name="fts_robotside")
    inertial = ET.SubElement(sensor, "inertial")
    ET.SubElement(inertial, "mass", value="0.3")
    ET.SubElement(inertial, "inertia", ixx="1e-4", ixy="0", ixz="0", iyy="1e-4", iyz="0", izz="1e-4")
    collision = ET.SubElement(sensor, "collision")
    ET.SubElement(collision, "origin", xyz="0 0 -0.04", rpy="0 0 0")
    ET.SubElement(ET.SubElement(collision, "geometry"), "mesh", filename=f"{mesh_uri}/fts.stl")
    joint = ET.SubElement(robot, "joint", name="fts_joint", type="fixed")
    ET.SubElement(joint, "parent", link="wrist_3_link")
    ET.SubElement(joint, "child", link="fts_robotside")
    ET.SubElement(joint, "origin", xyz="0 0 0", rpy="0 0 0")
    tree.write(pkg / "urdf" / "my_arm.urdf", xml_declaration=True, encoding="utf-8")
    (pkg / "config" / "my_arm.srdf").write_text(srdf)
    return pkg


def scene_text(package_dir: str = f"../{PACKAGE}", extra_robot: str = "") -> str:
    """A scene beside the package (in root/scenes/) that points at its files and edits none."""
    return f"""\
name: my_arm_pick
robot:
  model: ../{PACKAGE}/urdf/my_arm.urdf
  packages: {{{PACKAGE}: {package_dir}}}
  srdf: ../{PACKAGE}/config/my_arm.srdf
  base: {{xyz: [0, 0, 0]}}
  base_link: base_link
  end_effector: {{frame: tool_tcp, approach_axis: z, closing_axis: y, opening: 0.085}}
  start: ready
{extra_robot}objects:
- {{id: table_1, type: table, geometry: {{box: [0.8, 1.0, 0.04]}}, pose: {{xyz: [0.6, 0.0, -0.02]}}}}
- {{id: cup_1, type: cup, geometry: {{cylinder: {{radius: 0.033, length: 0.12}}}}, pose: {{xyz: [0.5, -0.2, 0.06]}}}}
planner: {{algorithm: bidirectional, step_size: 0.5, edge_resolution: 0.05, collision_padding: 0.005, time_limit: 30.0}}
"""
