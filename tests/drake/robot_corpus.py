"""Robot descriptions as they come, generated on the fly (issue #28's corpus).

Each entry writes one small description reproducing a feature real packages ship with —
xacro with required arguments and ``$(find)``, an SDF using ``drake:`` without declaring it,
mimic finger joints, continuous joints carrying huge URDF limits, a floating base, DAE and
missing visual meshes, duplicate transmission names, a hand that collides with itself — and a
tabletop scene with a cup around it. The arm is the bundled UR5e's kinematics (models/ur5e,
primitive geometry), rewritten as each feature needs; nothing from upstream packages.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import yaml

UR5E = Path(__file__).resolve().parents[2] / "lazyground" / "data" / "models" / "ur5e" / "ur5e.urdf"
PACKAGE = "corpus_arm_description"
ARM = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"]
READY = dict(zip(ARM, [0.0, -1.570796, 1.570796, -1.570796, -1.570796, 0.0]))
END_EFFECTOR = {"frame": "tool_tcp", "approach_axis": "z", "closing_axis": "y", "opening": 0.085}


def ur5e_text() -> str:
    """The bundled UR5e URDF without its comments."""
    return re.sub(r"<!--.*?-->", "", UR5E.read_text(), flags=re.S)


def _without_filter_groups(text: str) -> str:
    return re.sub(r"<drake:collision_filter_group.*?</drake:collision_filter_group>", "", text, flags=re.S)


def _package(root: Path) -> Path:
    pkg = root / PACKAGE
    (pkg / "urdf").mkdir(parents=True, exist_ok=True)
    (pkg / "meshes").mkdir(exist_ok=True)
    (pkg / "package.xml").write_text(f"<package format='3'><name>{PACKAGE}</name></package>")
    return pkg


def xacro_arm(root: Path) -> Path:
    """A ROS 2-style xacro: a required ``name`` argument, a defaulted ``tcp`` one, the body in a macro ``$(find)``-included."""
    pkg = _package(root)
    body = ur5e_text().split(">", 2)[2].rsplit("</robot>", 1)[0]  # after <?xml ...?> and <robot ...>
    body = body.replace('<origin xyz="0 0 0.125" rpy="0 0 0"/>', '<origin xyz="0 0 ${tcp}" rpy="0 0 0"/>')
    (pkg / "urdf" / "arm_macro.xacro").write_text(
        '<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro" xmlns:drake="http://drake.mit.edu">'
        f'<xacro:macro name="arm" params="tcp">{body}</xacro:macro></robot>')
    top = pkg / "urdf" / "arm.urdf.xacro"
    top.write_text(
        '<?xml version="1.0"?>\n<robot name="$(arg name)" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:arg name="tcp_offset" default="0.125"/>'
        f'<xacro:include filename="$(find {PACKAGE})/urdf/arm_macro.xacro"/>'
        '<xacro:arm tcp="$(arg tcp_offset)"/></robot>')
    return top


def _urdf(root: Path, name: str, text: str) -> Path:
    path = _package(root) / "urdf" / name
    path.write_text(text)
    return path


def _moving_fingers(text: str, mimic: bool) -> str:
    """Fingers on prismatic joints (finger_joint, right_finger_joint), the right one a ``<mimic>`` of the left if asked."""
    for side, sign in (("left", ""), ("right", "-")):
        joint = "finger_joint" if side == "left" else "right_finger_joint"
        extra = (f'<axis xyz="0 {sign}1 0"/><limit lower="-0.04" upper="0.01" effort="10" velocity="0.1"/>'
                 + ('<mimic joint="finger_joint" multiplier="1" offset="0"/>' if mimic and side == "right" else ""))
        text = text.replace(f'<joint name="gripper-{side}_finger" type="fixed">', f'<joint name="{joint}" type="prismatic">{extra}')
    return text


def mimic_arm(root: Path) -> Path:
    """Fingers on prismatic joints, the right one a ``<mimic>`` of the left."""
    return _urdf(root, "mimic.urdf", _moving_fingers(ur5e_text(), mimic=True))


def continuous_arm(root: Path) -> Path:
    """The pan and wrist-3 joints continuous, with +-174.5 rad written on them (as one vendor's arm has)."""
    text = ur5e_text()
    for joint in ("shoulder_pan_joint", "wrist_3_joint"):
        text = re.sub(rf'(<joint name="{joint}") type="revolute"(.*?)lower="[^"]+" upper="[^"]+"',
                      r'\1 type="continuous"\2lower="-174.5" upper="174.5"', text, count=1, flags=re.S)
    return _urdf(root, "continuous.urdf", text)


def visual_meshes_arm(root: Path) -> Path:
    """Every visual a mesh: DAE files (needing the [meshes] extra) and one that does not exist."""
    pkg = _package(root)
    (pkg / "meshes" / "link.dae").write_text("<COLLADA/>")  # not a readable mesh: a viewer-only problem
    text = re.sub(r"<visual>(<origin[^>]*/>)<geometry>.*?</geometry>",
                  rf'<visual>\1<geometry><mesh filename="package://{PACKAGE}/meshes/link.dae"/></geometry>', ur5e_text())
    text = text.replace("meshes/link.dae", "meshes/missing.stl", 1)
    return _urdf(root, "visual_meshes.urdf", text)


def transmission_arm(root: Path) -> Path:
    """Two transmissions naming the same actuator, a gazebo block and ros2_control: Drake refuses the duplicate."""
    block = ('<transmission name="trans"><type>transmission_interface/SimpleTransmission</type>'
             '<joint name="{j}"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>'
             '<actuator name="motor"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>')
    extra = "".join(block.format(j=j) for j in ARM[:2])
    extra += '<gazebo><plugin name="x" filename="libx.so"/></gazebo><ros2_control name="s" type="system"><hardware/></ros2_control>'
    text = ur5e_text().replace('<joint name="elbow_joint" type="revolute">',
                               '<joint name="elbow_joint" type="revolute"><safety_controller k_velocity="1"/>')
    return _urdf(root, "transmissions.urdf", text.replace("</robot>", extra + "</robot>"))


def self_colliding_arm(root: Path) -> Path:
    """Moving fingers whose knuckles (inside the palm) overlap each other in every pose, no Drake filter group (a ROS package has none)."""
    text = _moving_fingers(_without_filter_groups(ur5e_text()), mimic=False)
    for side, y in (("left", -0.0425), ("right", 0.0425)):
        knuckle = f'<collision name="knuckle"><origin xyz="0 {y} -0.05"/><geometry><box size="0.03 0.14 0.02"/></geometry></collision>'
        text = text.replace(f'<link name="gripper_{side}_finger">', f'<link name="gripper_{side}_finger">{knuckle}')
    return _urdf(root, "hand_collides.urdf", text)


def sdf_arm(root: Path) -> Path:
    """The arm as SDF 1.9 (frames by ``relative_to``) with ``drake:`` tags and no ``xmlns:drake``."""
    urdf = ET.fromstring(_without_filter_groups(ur5e_text()).replace("drake:", "drake_"))
    parts = ['<?xml version="1.0"?>\n<sdf version="1.9"><model name="arm">']
    joint_of = {j.find("child").get("link"): j for j in urdf.iter("joint")}
    for link in urdf.iter("link"):
        name = link.get("name")
        joint = joint_of.get(name)
        parts.append(f'<link name="{name}">' + (f'<pose relative_to="{joint.get("name")}"/>' if joint is not None else ""))
        for kind in ("visual", "collision"):
            for i, g in enumerate(link.iter(kind)):
                origin = g.find("origin")
                pose = f'{origin.get("xyz", "0 0 0")} {origin.get("rpy", "0 0 0")}' if origin is not None else "0 0 0 0 0 0"
                shape = g.find("geometry")[0]
                geometry = (f'<box><size>{shape.get("size")}</size></box>' if shape.tag == "box" else
                            f'<cylinder><radius>{shape.get("radius")}</radius><length>{shape.get("length")}</length></cylinder>')
                props = "<drake:proximity_properties><drake:mu_dynamic>0.5</drake:mu_dynamic></drake:proximity_properties>" if kind == "collision" else ""
                parts.append(f'<{kind} name="{kind}_{i}"><pose>{pose}</pose><geometry>{geometry}</geometry>{props}</{kind}>')
        parts.append("</link>")
    for joint in urdf.iter("joint"):
        origin = joint.find("origin")
        pose = f'{origin.get("xyz", "0 0 0")} {origin.get("rpy", "0 0 0")}' if origin is not None else "0 0 0 0 0 0"
        kind = joint.get("type")
        parts.append(f'<joint name="{joint.get("name")}" type="{kind}"><pose relative_to="{joint.find("parent").get("link")}">{pose}</pose>'
                     f'<parent>{joint.find("parent").get("link")}</parent><child>{joint.find("child").get("link")}</child>')
        if kind == "revolute":
            limit = joint.find("limit")
            parts.append(f'<axis><xyz>{joint.find("axis").get("xyz")}</xyz><limit><lower>{limit.get("lower")}</lower>'
                         f'<upper>{limit.get("upper")}</upper><velocity>{limit.get("velocity")}</velocity></limit></axis>')
        parts.append("</joint>")
    parts.append('<drake:collision_filter_group name="hand"><drake:member>wrist_3_link</drake:member>'
                 '<drake:member>gripper_palm</drake:member><drake:member>gripper_left_finger</drake:member>'
                 '<drake:member>gripper_right_finger</drake:member><drake:ignored_collision_filter_group>hand'
                 '</drake:ignored_collision_filter_group></drake:collision_filter_group>')
    parts.append("</model></sdf>")
    path = _package(root) / "arm.sdf"
    path.write_text("".join(parts))
    return path


def cup_scene(root: Path, model: Path, name: str, floating: bool = False, **robot) -> Path:
    """A tabletop with one red cup in reach of ``model``'s arm; ``robot`` keys override the robot block."""
    block = {"model": str(model), "base_link": "base_link", "planned_joints": ARM, "end_effector": END_EFFECTOR,
             "start": READY, **robot}
    block = {k: v for k, v in block.items() if v is not None}
    if not floating:
        block["base"] = {"xyz": [0.0, 0.0, 0.0]}
    scene = {
        "name": name,
        "robot": block,
        "objects": [
            {"id": "table_1", "type": "table", "geometry": {"box": [1.0, 1.3, 0.04]}, "pose": {"xyz": [0.7, 0.0, -0.02]}},
            {"id": "cup_1", "type": "cup", "color": "red", "geometry": {"cylinder": {"radius": 0.033, "length": 0.12}},
             "pose": {"xyz": [0.45, 0.25, 0.06]}},
        ],
        "planner": {"algorithm": "bidirectional", "step_size": 0.5, "edge_resolution": 0.05, "collision_padding": 0.005,
                    "time_limit": 60.0},
    }
    path = root / f"{name}.yaml"
    path.write_text(yaml.safe_dump(scene, sort_keys=False))
    return path


def arm_and_gripper(root: Path) -> tuple[Path, Path]:
    """The arm without its gripper (one package) and the gripper alone (another, with a robot.yaml naming its TCP).

    The gripper's fingers are prismatic, the right one a ``<mimic>`` of the left.
    """
    text = _moving_fingers(_without_filter_groups(ur5e_text()), mimic=True)
    urdf = ET.fromstring(text.replace("drake:", "drake_"))
    hand = {"gripper_palm", "gripper_left_finger", "gripper_right_finger", "tool_tcp"}
    arm, gripper = ET.Element("robot", {"name": "arm"}), ET.Element("robot", {"name": "gripper"})
    for element in urdf:
        name = element.get("name")
        child = element.find("child")
        in_hand = name in hand if element.tag == "link" else (child is not None and child.get("link") in hand)
        (gripper if in_hand else arm).append(element)
    for joint in list(gripper.findall("joint")):
        if joint.find("parent").get("link") == "tool0":  # the mount: the scene's robot.tools says it
            gripper.remove(joint)
    arm_path = _urdf(root, "arm_only.urdf", ET.tostring(arm, encoding="unicode"))
    pkg = root / "corpus_gripper_description"
    (pkg / "urdf").mkdir(parents=True, exist_ok=True)
    (pkg / "package.xml").write_text("<package format='3'><name>corpus_gripper_description</name></package>")
    gripper_path = pkg / "urdf" / "gripper.urdf"
    gripper_path.write_text(ET.tostring(gripper, encoding="unicode"))
    (pkg / "urdf" / "robot.yaml").write_text(yaml.safe_dump({"model": "gripper.urdf", "end_effector": END_EFFECTOR}))
    return arm_path, gripper_path
