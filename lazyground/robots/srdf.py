"""MoveIt SRDF files: the link pairs that never need checking, and the named robot states.

``read_srdf(path)`` returns the ``<disable_collisions link1 link2>`` pairs (MoveIt's
collision matrix; lazyground filters them in the collision checker) and every
``<group_state name group>`` with its ``<joint name value>`` entries (named poses such as
``ready`` or ``tucked``). Groups, end effectors and virtual joints are listed as
unsupported so ``check-robot`` can say so. No pydrake.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

from lazyground.typed_yaml import SceneError

IGNORED = ("group", "end_effector", "virtual_joint", "passive_joint", "link_sphere_approximation")


@dataclass(frozen=True)
class Srdf:
    """What lazyground takes from an SRDF."""

    robot: str
    disabled_collisions: tuple[tuple[str, str], ...] = ()
    named_poses: dict[str, dict[str, float]] = field(default_factory=dict)
    ignored: dict[str, int] = field(default_factory=dict)  # element name -> count (read, not used)
    source: str = ""


def read_srdf(path: str | Path) -> Srdf:
    """Read a MoveIt SRDF file.

    Args:
        path: the ``.srdf`` file.
    Returns:
        Its disabled collision pairs, named poses (a state in several groups merges the joints)
        and the elements that were read but are not used.
    Raises:
        SceneError: the file is missing, not XML, not an SRDF, or an entry lacks an attribute.
    """
    path = Path(path)
    if not path.is_file():
        raise SceneError(f"{path}: no such SRDF file")
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as exc:
        raise SceneError(f"{path}: not an XML file: {exc}") from None
    if root.tag != "robot":
        raise SceneError(f"{path}: not an SRDF file (its root element is <{root.tag}>, expected <robot>)")
    pairs: list[tuple[str, str]] = []
    poses: dict[str, dict[str, float]] = {}
    ignored: dict[str, int] = {}
    for element in root:
        if element.tag == "disable_collisions":
            pairs.append((_attr(path, element, "link1"), _attr(path, element, "link2")))
        elif element.tag == "group_state":
            pose = poses.setdefault(_attr(path, element, "name"), {})
            for joint in element.iter("joint"):
                value = _attr(path, joint, "value")
                try:
                    pose[_attr(path, joint, "name")] = float(value.split()[0])
                except (ValueError, IndexError):
                    raise SceneError(f"{path}: group_state {element.get('name')!r}: joint {joint.get('name')!r}: value {value!r} is not a number") from None
        elif isinstance(element.tag, str):
            ignored[element.tag] = ignored.get(element.tag, 0) + 1
    return Srdf(root.get("name", ""), tuple(pairs), poses, ignored, str(path))


def _attr(path: Path, element: ET.Element, name: str) -> str:
    value = element.get(name)
    if value is None:
        raise SceneError(f"{path}: <{element.tag}> without a {name!r} attribute")
    return value
