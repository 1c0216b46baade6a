"""MoveIt's text scene format (``.scene``) -> a planning-scene mapping like the YAML message (issue 34).

What RViz's "Scene Objects" panel exports and ``PlanningScene::saveGeometryToStream`` writes::

    NAME
    * OBJECT ID                  (the rest of the line, spaces allowed)
    x y z                        (MoveIt 2 / Noetic layout only: the object's pose)
    qx qy qz qw
    N                            (shapes)
    box | sphere | cylinder | cone | plane | mesh
    DIMENSIONS                   (box: x y z; sphere: r; cylinder, cone: radius length; plane: a b c d;
                                  mesh: V T, then V vertex lines and T triangle lines)
    x y z                        (the shape's pose in the object)
    qx qy qz qw
    r g b a                      (the object's colour; "0 0 0 0" = none; optional in the oldest files)
    M                            (MoveIt 2 / Noetic layout only: subframes, each "NAME" and a pose)
    .

The older layout has no object pose and no subframes; it is told apart as MoveIt does, by the line after
the first ``*`` line (a pose has spaces, a shape count does not). The result has ``world.collision_objects``
as ``moveit_msgs/PlanningScene`` YAML does (cylinder and cone dimensions ``[height, radius]``), with inline
meshes as ``vertices``/``triangles``; :mod:`lazyground.moveit.convert` reads it like a YAML scene.
"""

from __future__ import annotations

import math

from lazyground.typed_yaml import SceneError

PRIMITIVES = {"box": 3, "sphere": 1, "cylinder": 2, "cone": 2}


class _Reader:
    """Whitespace tokens of the text after the name line; ``* ID`` lines are one marker token each."""

    def __init__(self, lines: list[str], source: str):
        self.tokens: list[tuple[str, int]] = []  # (token, line number)
        for n, line in enumerate(lines, start=2):
            if line.lstrip().startswith("*"):
                self.tokens.append(("*" + line.lstrip()[1:].strip(), n))
            else:
                self.tokens += [(t, n) for t in line.split()]
        self.k, self.source = 0, source

    def peek(self) -> str | None:
        return self.tokens[self.k][0] if self.k < len(self.tokens) else None

    def word(self, what: str) -> str:
        if self.k >= len(self.tokens):
            raise SceneError(f"{self.source}: the file ends where {what} was expected (a .scene file ends with '.')")
        self.k += 1
        return self.tokens[self.k - 1][0]

    def number(self, what: str) -> float:
        line = self.tokens[self.k][1] if self.k < len(self.tokens) else "end"
        token = self.word(what)
        try:
            value = float(token)
        except ValueError:
            raise SceneError(f"{self.source}: line {line}: {what}: expected a number, got {token!r}") from None
        if not math.isfinite(value):
            raise SceneError(f"{self.source}: line {line}: {what}: expected a finite number, got {token!r}")
        return value

    def count(self, what: str) -> int:
        value = self.number(what)
        if value < 0 or value != int(value):
            raise SceneError(f"{self.source}: {what}: expected a count, got {value:g}")
        return int(value)

    def pose(self, what: str) -> dict:
        x, y, z = (self.number(f"{what} position") for _ in range(3))
        qx, qy, qz, qw = (self.number(f"{what} orientation") for _ in range(4))
        return {"position": {"x": x, "y": y, "z": z}, "orientation": {"x": qx, "y": qy, "z": qz, "w": qw}}

    def numeric_next(self) -> bool:
        try:
            float(self.peek() or "")
            return True
        except ValueError:
            return False


def parse_scene_text(text: str, source: str) -> dict:
    """A ``.scene`` text as a planning-scene mapping ``{name, world: {collision_objects: [...]}}``.

    Raises:
        SceneError: malformed text, one line naming the file, the line or the object.
    """
    lines = text.splitlines()
    if not lines:
        raise SceneError(f"{source}: the file is empty")
    name = lines[0].strip()
    rest = lines[1:]
    first = next((k for k, line in enumerate(rest) if line.lstrip().startswith("*")), None)
    new_layout = first is not None and first + 1 < len(rest) and " " in rest[first + 1].strip()
    reader = _Reader(rest, source)
    objects = []
    while True:
        marker = reader.word("an object ('* ID') or the end ('.')")
        if marker == ".":
            break
        if not marker.startswith("*"):
            raise SceneError(f"{source}: expected an object ('* ID') or the end ('.'), got {marker!r}")
        oid = marker[1:].strip()
        if not oid:
            raise SceneError(f"{source}: an object without an id ('* ' alone)")
        objects.append(_object(reader, oid, new_layout, f"object {oid!r}"))
    return {"name": name, "world": {"collision_objects": objects}}


def _object(reader: _Reader, oid: str, new_layout: bool, where: str) -> dict:
    entry = {"id": oid, "header": {"frame_id": "world"}, "primitives": [], "primitive_poses": [], "meshes": [],
             "mesh_poses": [], "planes": [], "plane_poses": []}
    if new_layout:
        entry["pose"] = reader.pose(f"{where}: pose")
    for k in range(reader.count(f"{where}: shape count")):
        kind = reader.word(f"{where}: shape {k + 1}'s type").lower()
        at = f"{where}: shape {k + 1} ({kind})"
        if kind in PRIMITIVES:
            dims = [reader.number(f"{at} dimensions") for _ in range(PRIMITIVES[kind])]
            if kind in ("cylinder", "cone"):  # the text has radius, length; the message [height, radius]
                dims = [dims[1], dims[0]]
            entry["primitives"].append({"type": kind, "dimensions": dims})
            poses = entry["primitive_poses"]
        elif kind == "mesh":
            nv, nt = reader.count(f"{at} vertex count"), reader.count(f"{at} triangle count")
            vertices = [[reader.number(f"{at} vertex") for _ in range(3)] for _ in range(nv)]
            triangles = [[reader.count(f"{at} triangle") for _ in range(3)] for _ in range(nt)]
            if any(i >= nv for t in triangles for i in t):
                raise SceneError(f"{reader.source}: {at}: a triangle refers to a vertex beyond the {nv} given")
            entry["meshes"].append({"vertices": vertices, "triangles": triangles})
            poses = entry["mesh_poses"]
        elif kind == "plane":
            entry["planes"].append({"coef": [reader.number(f"{at} coefficients") for _ in range(4)]})
            poses = entry["plane_poses"]
        else:
            raise SceneError(f"{reader.source}: {at}: unknown shape type (box, sphere, cylinder, cone, plane or mesh)")
        poses.append(reader.pose(f"{at} pose"))
        if new_layout or reader.numeric_next():  # the colour: always written since 2016, absent before
            rgba = [reader.number(f"{at} colour") for _ in range(4)]
            if any(rgba):
                entry["color"] = rgba
    if new_layout:
        for k in range(reader.count(f"{where}: subframe count")):
            reader.word(f"{where}: subframe {k + 1}'s name")
            reader.pose(f"{where}: subframe {k + 1}")
    for key in ("planes", "plane_poses"):
        if not entry[key]:
            del entry[key]
    return entry
