"""A can inside an open box, in variants (issue 34): robot, wall height, box size, where the can stands.

The held-out MoveIt scenes of issue 34 ended ``no_valid_goal`` on a can inside an open box where
other seeds solved. These variants vary what makes such a grasp hard: walls as high as the can or
lower, a snug or roomy box, the can centred, against a wall or in a corner, and the arm (Fetch at
a table, Panda and UR5e on the table top). Shared by tools/open_box_report.py and the scene tests.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from lazyground.bench.families.rack import FETCH_START, PANDA_START

CAN_R, CAN_L = 0.033, 0.12
WALL, BOTTOM = 0.01, 0.01  # m: wall and bottom thickness
GAP = 0.01  # m: the can's distance to a wall it stands against
UR5E_START = {"shoulder_pan_joint": 0.0, "shoulder_lift_joint": -1.570796, "elbow_joint": 1.570796,
              "wrist_1_joint": -1.570796, "wrist_2_joint": -1.570796, "wrist_3_joint": 0.0}
# per robot: the robot block, the table top's height, the box centre's x ahead of the base: near, far
# (the Fetch's far box is out of reach straight down: its can is grasped at a slant or not at all)
ROBOTS = {
    "fetch": ({"model": "fetch", "base": {"xyz": [0.0, 0.0, 0.0]}, "start": {**FETCH_START, "torso_lift_joint": 0.1}},
              0.72, {"near": 0.7, "far": 0.95}),
    "panda": ({"model": "panda", "base": {"xyz": [0.0, 0.0, 0.0]}, "base_link": "panda_link0", "start": PANDA_START},
              0.0, {"near": 0.5, "far": 0.75}),
    "ur5e": ({"model": "ur5e", "base": {"xyz": [0.0, 0.0, 0.0]}, "start": UR5E_START}, 0.0, {"near": 0.5, "far": 0.75}),
}
# where the can stands: unit offsets towards the walls (+x: away from the robot, +y: its left)
PLACES = {"centre": (0, 0), "far wall": (1, 0), "near wall": (-1, 0), "corner": (1, 1)}


@dataclass(frozen=True)
class OpenBox:
    """One variant: ``robot``, inner ``size`` (m, square), wall ``height`` above the bottom (m), ``place`` of the
    can, ``distance`` of the box ("near" or "far")."""

    robot: str
    size: float
    height: float
    place: str
    distance: str = "near"

    @property
    def name(self) -> str:
        return f"{self.robot} {self.distance} box {self.size:g} walls {self.height:g} {self.place}"


def variants(robots=tuple(ROBOTS), sizes=(0.20,), heights=(0.06, 0.09, 0.12), places=tuple(PLACES),
             distances=("near", "far")) -> list[OpenBox]:
    """Every combination, robot by robot."""
    return [OpenBox(r, s, h, p, d) for r, d, s, h, p in itertools.product(robots, distances, sizes, heights, places)]


def _box(id_, xyz, size) -> dict:
    return {"id": id_, "geometry": {"box": [round(s, 4) for s in size]}, "pose": {"xyz": [round(c, 4) for c in xyz]}, "color": "brown"}


def scene_dict(v: OpenBox) -> dict:
    """The scene: a table, the open box on it, the can inside."""
    robot, top, xs = ROBOTS[v.robot]
    bx, by = xs[v.distance], 0.0
    s, h = v.size, v.height
    outer = s + 2 * WALL
    floor = top + BOTTOM
    wz = floor + h / 2
    obstacles = [
        _box("box_bottom", (bx, by, top + BOTTOM / 2), (outer, outer, BOTTOM)),
        _box("box_wall_far", (bx + (s + WALL) / 2, by, wz), (WALL, outer, h)),
        _box("box_wall_near", (bx - (s + WALL) / 2, by, wz), (WALL, outer, h)),
        _box("box_wall_left", (bx, by + (s + WALL) / 2, wz), (s, WALL, h)),
        _box("box_wall_right", (bx, by - (s + WALL) / 2, wz), (s, WALL, h)),
    ]
    ux, uy = PLACES[v.place]
    reach = s / 2 - GAP - CAN_R  # the can's centre this far from the box's towards a wall
    can = (bx + ux * reach, by + uy * reach, floor + CAN_L / 2)
    objects = [
        {"id": "table", "type": "table", "geometry": {"box": [0.7, 1.2, 0.04]}, "pose": {"xyz": [bx + 0.15, by, top - 0.02]}},
        {"id": "can", "type": "can", "geometry": {"cylinder": {"radius": CAN_R, "length": CAN_L}},
         "pose": {"xyz": [round(c, 4) for c in can]}},
    ]
    return {"name": v.name.replace(" ", "_"), "description": f"A can inside an open box: {v.name}.",
            "robot": robot, "obstacles": obstacles, "objects": objects}
