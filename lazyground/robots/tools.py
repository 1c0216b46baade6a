"""Tools from their own packages mounted on an arm, and mimic joints (#28).

A gripper usually ships in another package than the arm it goes on. :func:`mount_tools`
merges prepared tool descriptions (URDF) into the arm's prepared URDF: the tool's links and
joints are added, its own ``world`` link and joints from it dropped, and a fixed joint from
the arm's ``parent`` link to the tool's root link placed at the given pose. One model then
reaches Drake, so the planner sees arm and gripper as one robot. :func:`mimic_joints` reads
``<mimic>`` relations so that a follower takes ``multiplier * leader + offset`` (Drake
ignores ``<mimic>`` in a continuous-time plant). No pydrake.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, replace

from lazyground.robots.lenient_xml import parse_lenient
from lazyground.typed_yaml import SceneError


@dataclass(frozen=True)
class Mimic:
    """A joint that follows another: ``q = multiplier * q_leader + offset``."""

    joint: str
    leader: str
    multiplier: float = 1.0
    offset: float = 0.0


def _link(element, tag: str) -> str | None:
    child = element.find(tag)
    return child.get("link") if child is not None else None


def root_link(root: ET.Element) -> str:
    """The URDF's root link (no joint has it as child), ``world`` left out.

    Raises:
        SceneError: none, or several roots.
    """
    children = {_link(j, "child") for j in root.findall("joint") if _link(j, "parent") != "world"}
    roots = [link.get("name") for link in root.findall("link") if link.get("name") not in children and link.get("name") != "world"]
    if len(roots) != 1:
        raise SceneError(f"expected one root link, found {len(roots)} ({', '.join(roots) or 'none'})")
    return roots[0]


def mount_tools(arm, tools, where: str = "robot.tools"):
    """The arm's PreparedModel with each (PreparedModel, parent link, xyz, rpy) tool fixed on it.

    Raises:
        SceneError: a tool that is not a URDF, an unknown parent link, or a link or joint name in both.
    """
    if not tools:
        return arm
    if arm.file_type != "urdf":
        raise SceneError(f"{where}: tools mount on a URDF or xacro robot model, not an {arm.file_type.upper()}")
    root = parse_lenient(arm.text)
    meshes, converted, packages, notes, stripped = dict(arm.meshes), list(arm.converted), dict(arm.packages), list(arm.notes), dict(arm.stripped)
    for i, (tool, parent, xyz, rpy) in enumerate(tools):
        here = f"{where}[{i}]"
        if tool.file_type != "urdf":
            raise SceneError(f"{here}.model: a tool must be a URDF or xacro file")
        links = {e.get("name") for e in root.findall("link")}
        if parent not in links:
            raise SceneError(f"{here}.parent: no link {parent!r} in the robot model")
        tool_root = parse_lenient(tool.text)
        try:
            first = root_link(tool_root)
        except SceneError as exc:
            raise SceneError(f"{here}.model: {exc}") from None
        joints = {e.get("name") for e in root.findall("joint")}
        materials = {e.get("name") for e in root.findall("material")}
        for element in tool_root:
            name = element.get("name")
            if element.tag == "link" and name == "world" or element.tag == "joint" and _link(element, "parent") == "world":
                continue
            if element.tag == "material" and name in materials:
                continue
            if element.tag == "link" and name in links or element.tag == "joint" and name in joints:
                raise SceneError(f"{here}.model: {element.tag} {name!r} is in both the robot and the tool")
            root.append(element)
        mount = ET.SubElement(root, "joint", {"name": f"{parent}-{first}", "type": "fixed"})
        ET.SubElement(mount, "parent", {"link": parent})
        ET.SubElement(mount, "child", {"link": first})
        ET.SubElement(mount, "origin", {"xyz": " ".join(map(str, xyz)), "rpy": " ".join(map(str, rpy))})
        meshes.update(tool.meshes)
        converted += tool.converted
        packages.update(tool.packages)
        notes += tool.notes
        for tag, n in tool.stripped.items():
            stripped[tag] = stripped.get(tag, 0) + n
    return replace(arm, text=ET.tostring(root, encoding="unicode"), meshes=meshes, converted=tuple(converted),
                   packages=packages, notes=tuple(notes), stripped=stripped)


def mimic_joints(text: str, file_type: str) -> tuple[Mimic, ...]:
    """The ``<mimic>`` relations of a URDF's joints."""
    if file_type != "urdf":
        return ()
    out = []
    for joint in parse_lenient(text).iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None and mimic.get("joint"):
            out.append(Mimic(joint.get("name"), mimic.get("joint"), float(mimic.get("multiplier", 1.0)), float(mimic.get("offset", 0.0))))
    return tuple(out)
