"""Generated racks of cubbies around an arm: N cans, k of them reachable (issue #33).

Cubbies stand in rings around the robot (the Panda: all round; the Fetch: the
front half its shoulder pans over), a few levels high, one can in each. In the
inner ring the ``reachable`` cubbies are open; the others are glazed, either
with a window that admits the wrist but not the hand (the can's side grasps are
collision-free but no path reaches them: the hand cannot pass the glass) or
closed (caged: no grasp is free). The Panda's pane is set back ``pane_back``
inside the cubby, where only link 7 crosses it at a side grasp (its wrist joint
and link 6 stay in front, the hand behind); at the front plane link 6 stood in
the window and no grasp was free. Outer rings stand behind the inner ring's back
wall (blocked behind others). The layout is seeded.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lazyground.settings import Algorithm, Strategy

BOARD = 0.02
CUBBY_W, CUBBY_D, CUBBY_H = 0.34, 0.30, 0.30
CAN_R, CAN_L = 0.033, 0.12
REACHABLE, WINDOW, CAGED, BEHIND = "reachable", "window", "caged", "behind"


@dataclass(frozen=True)
class ArmLayout:
    """Where one robot's rack stands."""

    radius: float  # the inner ring's front plane from the base
    floors: tuple[float, ...]  # each level's board top
    sweep: float  # the azimuth range (rad) the rack covers, centred ahead
    window: float  # the window's side: the wrist passes, the hand does not
    window_z: float  # the window's centre above the cubby floor (the side grasps' height)
    pane_back: float  # the pane's depth behind the cubby's front plane (between the wrist joint and the hand)
    can_back: float  # the can's centre behind the front plane: the hand inside at the pre-grasp, the wrist in the window
    robot: dict


PANDA_START = {"panda_joint1": 0.0, "panda_joint2": -0.785398, "panda_joint3": 0.0, "panda_joint4": -2.356194,
               "panda_joint5": 0.0, "panda_joint6": 1.570796, "panda_joint7": 0.785398}
FETCH_START = {"torso_lift_joint": 0.05, "shoulder_pan_joint": 1.32, "shoulder_lift_joint": 1.4, "upperarm_roll_joint": -0.2,
               "elbow_flex_joint": 1.72, "forearm_roll_joint": 0.0, "wrist_flex_joint": 1.66, "wrist_roll_joint": 0.0}
LAYOUTS = {
    "panda": ArmLayout(0.40, (0.05, 0.37, 0.69), 2 * math.pi * 0.9, 0.14, 0.085, 0.06, 0.20, {
        "model": "panda", "base": {"xyz": [0.0, 0.0, 0.0]}, "base_link": "panda_link0",
        "planned_joints": list(PANDA_START), "end_effector": "panda_hand_tcp", "start": PANDA_START}),
    "fetch": ArmLayout(0.55, (0.40, 0.72, 1.04), 2.8, 0.12, 0.06, -0.005, 0.19, {
        "model": "fetch", "base": {"xyz": [0.0, 0.0, 0.0]}, "base_link": "base_link",
        "planned_joints": list(FETCH_START), "end_effector": "gripper_link", "start": FETCH_START}),
}


@dataclass(frozen=True)
class RackSpec:
    """What to generate: the robot, the number of cans, how many reachable, the seed."""

    robot: str
    objects: int
    reachable: int = 1
    seed: int = 0
    caged: float = 0.25  # the fraction of the inner ring's blocked cubbies that are closed (the rest have a window)

    def __post_init__(self):
        if self.robot not in LAYOUTS:
            raise ValueError(f"robot must be one of {', '.join(LAYOUTS)}, got {self.robot!r}")
        if not 1 <= self.objects <= 1024:
            raise ValueError(f"objects must be in [1, 1024], got {self.objects}")
        if not 0 <= self.reachable <= self.objects:
            raise ValueError(f"reachable must be in [0, objects={self.objects}], got {self.reachable}")


def _box(id_, center, yaw, size, color="grey") -> dict:
    return {"id": id_, "geometry": {"box": [round(s, 4) for s in size]},
            "pose": {"xyz": [round(float(c), 4) for c in center], "rpy": [0, 0, round(yaw, 6)]}, "color": color}


def _columns(radius: float, sweep: float) -> np.ndarray:
    """Column azimuths of a ring whose front plane is ``radius`` out, ordered from straight ahead outwards."""
    step = 2 * math.atan((CUBBY_W / 2 + BOARD) / radius)
    n = max(1, int(sweep // step))
    az = (np.arange(n) - (n - 1) / 2) * step
    return az[np.argsort(np.abs(az), kind="stable")]


def _cells(layout: ArmLayout, n: int) -> list[tuple[int, float, float, float]]:
    """(ring, front radius, azimuth, floor) of the first n cubbies, inner ring first, ahead first."""
    out, ring = [], 0
    while len(out) < n:
        radius = layout.radius + ring * (CUBBY_D + 2 * BOARD)
        for az in _columns(radius, layout.sweep):
            for floor in layout.floors:
                out.append((ring, radius, float(az), floor))
        ring += 1
    return out[:n]


def _cubby(cid: str, radius: float, az: float, floor: float, kind: str, layout: ArmLayout) -> list[dict]:
    """The boards of one cubby, and its glazing (none when open)."""
    u, t = np.array([math.cos(az), math.sin(az)]), np.array([-math.sin(az), math.cos(az)])
    mid = radius + CUBBY_D / 2

    def at(radial, lateral, z):
        xy = u * radial + t * lateral
        return (xy[0], xy[1], z)

    boxes = [
        _box(f"{cid}_floor", at(mid, 0, floor - BOARD / 2), az, (CUBBY_D, CUBBY_W + 2 * BOARD, BOARD)),
        _box(f"{cid}_roof", at(mid, 0, floor + CUBBY_H + BOARD / 2), az, (CUBBY_D, CUBBY_W + 2 * BOARD, BOARD)),
        _box(f"{cid}_back", at(radius + CUBBY_D + BOARD / 2, 0, floor + CUBBY_H / 2), az, (BOARD, CUBBY_W + 2 * BOARD, CUBBY_H)),
    ]
    for k, side in enumerate((-1, 1)):
        boxes.append(_box(f"{cid}_side{k}", at(mid, side * (CUBBY_W + BOARD) / 2, floor + CUBBY_H / 2), az, (CUBBY_D, BOARD, CUBBY_H)))
    glass, front = "blue", radius - 0.005
    if kind == CAGED or kind == BEHIND:
        boxes.append(_box(f"{cid}_glass", at(front, 0, floor + CUBBY_H / 2), az, (0.01, CUBBY_W, CUBBY_H), glass))
    elif kind == WINDOW:  # a pane set back inside, with a square hole round the wrist at the grasp height
        w, plane = layout.window, radius + layout.pane_back
        lo, hi = layout.window_z - w / 2, layout.window_z + w / 2  # the hole's edges above the floor
        side = (CUBBY_W - w) / 2
        boxes.append(_box(f"{cid}_pane_top", at(plane, 0, floor + (hi + CUBBY_H) / 2), az, (0.01, CUBBY_W, CUBBY_H - hi), glass))
        if lo > 0:
            boxes.append(_box(f"{cid}_pane_low", at(plane, 0, floor + lo / 2), az, (0.01, CUBBY_W, lo), glass))
        for k, s in enumerate((-1, 1)):
            boxes.append(_box(f"{cid}_pane{k}", at(plane, s * (w + side) / 2, floor + (lo + hi) / 2), az, (0.01, side, w), glass))
    return boxes


def generate_rack(spec: RackSpec) -> dict:
    """The scene (a dict for the scene YAML) of a rack with ``spec.objects`` cans, ``spec.reachable`` reachable."""
    layout = LAYOUTS[spec.robot]
    rng = np.random.default_rng(spec.seed)
    cells = _cells(layout, spec.objects)
    inner = [i for i, c in enumerate(cells) if c[0] == 0]
    if spec.reachable > len(inner):
        raise ValueError(f"only {len(inner)} cubbies face the {spec.robot}: at most that many can be reachable")
    kinds = [BEHIND] * len(cells)
    order = rng.permutation(inner)
    for n, i in enumerate(order):
        kinds[i] = REACHABLE if n < spec.reachable else (CAGED if rng.random() < spec.caged else WINDOW)
    obstacles, objects = [], []
    for i, ((ring, radius, az, floor), kind) in enumerate(zip(cells, kinds)):
        cid = f"c{i}"
        obstacles += _cubby(cid, radius, az, floor, kind, layout)
        r = radius + layout.can_back
        objects.append({"id": f"can_{i}", "type": "can", "color": "red" if kind == REACHABLE else "yellow",
                        "geometry": {"cylinder": {"radius": CAN_R, "length": CAN_L}},
                        "pose": {"xyz": [round(r * math.cos(az), 4), round(r * math.sin(az), 4), round(floor + CAN_L / 2, 4)]}})
    counts = {k: kinds.count(k) for k in (REACHABLE, WINDOW, CAGED, BEHIND)}
    return {
        "name": f"rack_{spec.robot}_{spec.objects}_{spec.reachable}_s{spec.seed}",
        "description": (f"Generated rack (issue #33): {spec.objects} cans round a {spec.robot}, {counts[REACHABLE]} reachable; "
                        f"blocked: {counts[WINDOW]} behind a window, {counts[CAGED]} caged, {counts[BEHIND]} behind others; "
                        f"seed {spec.seed}."),
        "robot": dict(layout.robot),
        "obstacles": obstacles,
        "objects": objects,
        "planner": {"strategy": Strategy.REWARD_PENALTY.value, "algorithm": Algorithm.BIDIRECTIONAL.value, "goal_bias": 0.05,
                    "step_size": 0.5, "edge_resolution": 0.05, "time_limit": 30.0, "seed": 0, "collision_padding": 0.005},
        "expect": [{"request": "pick up a can", "success_rate": 0.9, "seeds": 3, "time_limit": 60.0,
                    "reachable": sorted(f"can_{i}" for i, k in enumerate(kinds) if k == REACHABLE)}],
    }


def can_kinds(scene: dict) -> dict[str, str]:
    """Each can's kind, read back from a generated scene (for tests and reports)."""
    ids = {o["id"] for o in scene["obstacles"]}
    reach = set(scene["expect"][0]["reachable"])
    out = {}
    for o in scene["objects"]:
        c = "c" + o["id"].split("_")[1]
        out[o["id"]] = (REACHABLE if o["id"] in reach else WINDOW if f"{c}_pane0" in ids
                        else CAGED if f"{c}_glass" in ids and c in _inner_ids(scene) else BEHIND)
    return out


def _inner_ids(scene: dict) -> set[str]:
    """The cubbies of the inner ring (their can nearest the base ring radius)."""
    rs = {o["id"]: math.hypot(*o["pose"]["xyz"][:2]) for o in scene["objects"]}
    r0 = min(rs.values())
    return {"c" + k.split("_")[1] for k, r in rs.items() if r < r0 + CUBBY_D / 2}
