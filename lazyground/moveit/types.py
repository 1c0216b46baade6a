"""Object types for imported ids (#15): rules match id *tokens* and check geometry.

An id is split into lower-case tokens at separators, case changes and digits
(``table_leg_1`` -> table, leg, 1; ``Can1`` -> can, 1). A part word (leg, wall,
bar, vert, ...) makes the object an untyped obstacle whatever else it names;
otherwise the first type word decides. Geometry then has the last word: a support
(table, shelf, counter) must be a box wider than it is tall (a vertical board is
an obstacle), and a pickable object must fit the gripper's opening. User rules
(``--type 'REGEX=TYPE'``, a rules file) are searched in the whole id first and
are taken as given, except that meshes stay obstacles.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

import yaml

from lazyground.typed_yaml import SceneError, load_yaml

OBSTACLE = "obstacle"
PART_WORDS = frozenset({"leg", "legs", "wall", "walls", "bar", "bars", "post", "posts", "vert", "vertical", "panel", "back",
                        "side", "divider", "bracket", "frame", "door", "handle", "bottom", "base", "rail", "pole"})
TYPE_WORDS: dict[str, str] = {
    "can": "can", "cans": "can", "soda": "can", "coke": "can",
    "box": "box", "boxes": "box", "cube": "box", "crate": "box",
    "shelf": "shelf", "shelves": "shelf", "board": "shelf",
    "table": "table", "desk": "table",
    "bottle": "bottle", "cup": "cup", "mug": "cup",
    "counter": "counter", "cabinet": "cabinet",
}
SUPPORTS = frozenset({"table", "shelf", "counter", "cabinet"})
PICKABLE = frozenset({"can", "box", "bottle", "cup"})
GRIP_CLEARANCE = 0.01  # m the fingers need beside the object (#15)


@dataclass(frozen=True)
class UserRule:
    """``REGEX=TYPE``: an id the regex finds (case-insensitive) gets TYPE (``obstacle`` = untyped)."""

    pattern: re.Pattern
    type: str


def tokens(object_id: str) -> list[str]:
    """``small_shelf_2`` -> [small, shelf, 2]; ``Shelf1_4`` -> [shelf, 1, 4]; ``tableLeg`` -> [table, leg]."""
    spaced = re.sub(r"([a-z])([A-Z])", r"\1 \2", object_id)
    return [t.lower() for t in re.findall(r"[A-Za-z]+|\d+", spaced)]


def word_type(object_id: str) -> str:
    """The type the id's words say, before any geometry check."""
    words = tokens(object_id)
    if PART_WORDS.intersection(words):
        return OBSTACLE
    return next((TYPE_WORDS[w] for w in words if w in TYPE_WORDS), OBSTACLE)


def parse_rule(text: str, where: str = "--type") -> UserRule:
    """``'REGEX=TYPE'`` as a rule.

    Raises:
        SceneError: no ``=``, an empty side or an invalid regex (one line).
    """
    pattern, sep, type_name = text.rpartition("=")
    if not sep or not pattern or not type_name.strip():
        raise SceneError(f"{where}: expected 'REGEX=TYPE', got {text!r}")
    try:
        return UserRule(re.compile(pattern, re.IGNORECASE), type_name.strip())
    except re.error as exc:
        raise SceneError(f"{where}: {pattern!r} is not a regular expression: {exc}") from None


def load_rules_file(path: str | Path) -> list[UserRule]:
    """A rules file: YAML mapping ``REGEX: TYPE`` (tried in order).

    Raises:
        SceneError: unreadable, not a mapping, or a bad rule.
    """
    try:
        data = load_yaml(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise SceneError(f"{path}: cannot read type rules: {str(exc).splitlines()[0]}") from None
    if not isinstance(data, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in data.items()):
        raise SceneError(f"{path}: type rules must be a mapping of 'REGEX: TYPE' strings")
    return [parse_rule(f"{k}={v}", f"{path}: {k}") for k, v in data.items()]


def classify(object_id: str, extents: tuple[float, float, float], kind: str, opening: float | None,
             user_rules=()) -> tuple[str, str | None]:
    """(type, note) for one imported primitive.

    Args:
        object_id: the MoveIt object id.
        extents: the primitive's world axis-aligned size (x, y, z) in metres.
        kind: box, cylinder, sphere or mesh.
        opening: the gripper's widest grasp (m; None = unknown, no check).
        user_rules: UserRules tried first, taken as given.

    Returns:
        The type (``obstacle`` = untyped) and a note when geometry overruled the id's words.
    """
    rule = next((r for r in user_rules if r.pattern.search(object_id)), None)
    type_name = rule.type if rule else word_type(object_id)
    if type_name == OBSTACLE:
        return OBSTACLE, None
    if kind == "mesh":  # a scene's typed objects are primitives (grasp and support regions need their shape)
        return OBSTACLE, f"{object_id}: a mesh, imported as an obstacle (meshes cannot be {type_name}s)"
    if rule:
        return type_name, None
    sx, sy, sz = extents
    if type_name in SUPPORTS and (kind != "box" or sz > min(sx, sy)):
        return OBSTACLE, (f"{object_id}: {sx:.2f} x {sy:.2f} x {sz:.2f} m is not a horizontal board: "
                          f"imported as an obstacle, not a {type_name}")
    if type_name in PICKABLE and opening is not None:
        width = min(sx, sy)
        if width > opening - GRIP_CLEARANCE:
            return OBSTACLE, (f"{object_id}: {width:.2f} m wide, the gripper opens {opening:.2f} m "
                              f"(less {GRIP_CLEARANCE:.2f} clearance): imported as an obstacle, not a {type_name}")
    return type_name, None
