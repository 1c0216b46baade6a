"""What a file given to the importer is (#15): a MoveIt planning scene, a motion-plan
request, URDF/SDF/SRDF XML, or something else, said in one line."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from enum import Enum


class FileKind(Enum):
    PLANNING_SCENE = "a MoveIt planning scene"
    MOTION_PLAN_REQUEST = "a MoveIt motion-plan request (moveit_msgs/MotionPlanRequest)"
    URDF = "a URDF robot model"
    SRDF = "an SRDF (MoveIt semantic robot description)"
    SDF = "an SDF model"
    XML = "an XML file"
    SCENE_TEXT = "MoveIt's text scene format (.scene: RViz's scene objects export)"
    OTHER = "not a MoveIt planning scene"


SCENE_KEYS = {"world", "robot_state", "robot_model_name", "fixed_frame_transforms", "allowed_collision_matrix", "is_diff"}
REQUEST_KEYS = {"start_state", "goal_constraints", "group_name", "planner_id", "workspace_parameters", "path_constraints"}


def kind_of_text(text: str) -> FileKind:
    """The kind of a file from its text (XML is told by its root element)."""
    head = text.lstrip()
    if head.startswith("<"):
        try:
            root = ET.fromstring(text)
        except ET.ParseError:
            return FileKind.XML
        if root.tag == "sdf":
            return FileKind.SDF
        if root.tag == "robot":
            semantic = {"group", "group_state", "disable_collisions", "end_effector", "virtual_joint"}
            return FileKind.SRDF if any(c.tag in semantic for c in root) and root.find("link") is None else FileKind.URDF
        return FileKind.XML
    lines = [line.rstrip() for line in text.strip().splitlines()]
    if len(lines) > 2 and lines[-1] == "." and any(line.startswith("* ") for line in lines):  # objects "* id", ends "."
        return FileKind.SCENE_TEXT
    return FileKind.OTHER


def kind_of_mapping(data) -> FileKind:
    """The kind of a parsed YAML document."""
    if not isinstance(data, dict):
        return FileKind.OTHER
    keys = set(data)
    if keys & REQUEST_KEYS and "world" not in keys:
        return FileKind.MOTION_PLAN_REQUEST
    if keys & SCENE_KEYS:
        return FileKind.PLANNING_SCENE
    return FileKind.OTHER


def not_a_scene_message(kind: FileKind, data=None) -> str:
    """One line for a file that is not a planning scene: what it is, and what to do."""
    hint = {
        FileKind.MOTION_PLAN_REQUEST: "give it as --start-from REQUEST.yaml together with the planning scene",
        FileKind.URDF: "robots are chosen with --robot; give the planning scene (world.collision_objects) as FILE",
        FileKind.SRDF: "named poses come from models/<robot>/robot.yaml; give the planning scene as FILE",
        FileKind.SDF: "give the MoveIt planning scene (world.collision_objects) as FILE",
        FileKind.XML: "expected a MoveIt planning scene in YAML",
        FileKind.SCENE_TEXT: "give the scene as a moveit_msgs/PlanningScene message in YAML (world.collision_objects, "
                             "robot_state), e.g. echoed from the planning-scene topic",
    }.get(kind)
    if hint is None:
        top = f"top-level keys: {', '.join(sorted(map(str, data))[:6])}" if isinstance(data, dict) and data else \
            f"a YAML {type(data).__name__}" if data is not None else "an empty document"
        return f"not a MoveIt planning scene ({top}; expected world.collision_objects and robot_state)"
    return f"this is {kind.value}, not a planning scene: {hint}"
