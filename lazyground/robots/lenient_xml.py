"""Reading a description no stricter than Drake's parser, and removing what planning does not use.

Drake's URDF/SDF readers (tinyxml2, sdformat) ignore XML namespaces, so Drake's own model
files use ``drake:`` without declaring it; ElementTree refuses such a file ("unbound
prefix"). :func:`parse_lenient` declares every undeclared prefix first. Tags planning does
not need and that can stop Drake's parser (a ``<transmission>`` whose actuator name repeats,
``<gazebo>``, ``<ros2_control>``, a joint's ``<safety_controller>`` and ``<dynamics>``) are removed by
:func:`strip_unused`; a URDF ``continuous`` joint's position limits are dropped by
:func:`unwrap_continuous_limits` (a continuous joint turns freely; Drake would keep them).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from collections import Counter

KNOWN_NAMESPACES = {"drake": "http://drake.mit.edu"}
UNUSED_TOP = ("transmission", "gazebo", "ros2_control")  # children of <robot>
UNUSED_IN_JOINT = ("safety_controller", "dynamics")  # dynamics: damping/friction Drake warns about; planning has no use
_PREFIX = re.compile(r"</?([A-Za-z_][\w.-]*):[A-Za-z_]|\s([A-Za-z_][\w.-]*):[A-Za-z_][\w.-]*\s*=")
_DECLARED = re.compile(r"xmlns:([A-Za-z_][\w.-]*)\s*=")
_ROOT = re.compile(r"<(?![?!])[A-Za-z_][\w.:-]*")


def declare_prefixes(text: str) -> str:
    """``text`` with every namespace prefix it uses but does not declare declared on its root element."""
    used = {a or b for a, b in _PREFIX.findall(text)} - {"xmlns", "xml"}
    missing = sorted(used - set(_DECLARED.findall(text)))
    if not missing:
        return text
    root = _ROOT.search(text)
    if root is None:
        return text
    decl = "".join(f' xmlns:{p}="{KNOWN_NAMESPACES.get(p, "urn:undeclared:" + p)}"' for p in missing)
    return text[:root.end()] + decl + text[root.end():]



def parse_lenient(text: str) -> ET.Element:
    """The root element of ``text``, undeclared prefixes declared first (see module docstring).

    Raises:
        ET.ParseError: the text is not XML.
    """
    return ET.fromstring(declare_prefixes(text))


def strip_unused(root: ET.Element) -> dict[str, int]:
    """Remove the tags planning does not use from a URDF tree; returns how many of each were removed."""
    removed: Counter = Counter()
    for child in list(root):
        if child.tag in UNUSED_TOP:
            root.remove(child)
            removed[child.tag] += 1
    for joint in root.iter("joint"):
        for child in list(joint):
            if child.tag in UNUSED_IN_JOINT:
                joint.remove(child)
                removed[child.tag] += 1
    return dict(removed)


def unwrap_continuous_limits(root: ET.Element) -> list[str]:
    """Drop the position limits of URDF ``continuous`` joints; one note naming the joints that had them."""
    changed = []
    for joint in root.iter("joint"):
        limit = joint.find("limit")
        if joint.get("type") != "continuous" or limit is None:
            continue
        if limit.get("lower") is not None or limit.get("upper") is not None:
            changed.append(f"{joint.get('name')} [{limit.get('lower', '-inf')}, {limit.get('upper', 'inf')}]")
            limit.attrib.pop("lower", None)
            limit.attrib.pop("upper", None)
    if not changed:
        return []
    return [f"continuous joints wrap (their URDF position limits are ignored): {', '.join(changed)}"]


def drop_world_weld(root: ET.Element, link: str) -> str | None:
    """Remove a URDF's fixed joint from its ``world`` link to ``link`` (the scene's ``robot.base`` places it instead).

    Returns:
        A note when a joint was removed (the ``world`` link goes too when nothing else hangs on it).
    """
    welds = [j for j in root.findall("joint") if j.get("type") == "fixed"
             and getattr(j.find("parent"), "get", lambda _: None)("link") == "world"
             and getattr(j.find("child"), "get", lambda _: None)("link") == link]
    if not welds:
        return None
    for joint in welds:
        root.remove(joint)
    if not any(getattr(j.find("parent"), "get", lambda _: None)("link") == "world" for j in root.findall("joint")):
        for world in [e for e in root.findall("link") if e.get("name") == "world"]:
            root.remove(world)
    return f"the model's fixed joint {welds[0].get('name')!r} from world to {link} is replaced by robot.base"
