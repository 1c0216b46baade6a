"""Write the MoveIt planning-scene test corpus (#15): tests/data/moveit_corpus/.

    python3 tools/make_moveit_corpus.py

Layouts real Fetch users have, in the formats they save them in: ``moveit_msgs/PlanningScene``
YAML (``world.collision_objects[]`` with ``primitives``/``primitive_poses`` and
``meshes``/``mesh_poses`` referring to files), ``moveit_msgs/MotionPlanRequest`` YAML for a
start state, and the mesh files themselves (OBJ and binary STL; some referenced ones are
missing on purpose). The Fetch's base_link is at the origin; the arm reaches about 1 m.
``corpus.yaml`` lists each scene with its natural request and import options.
"""

from __future__ import annotations

import struct
from pathlib import Path

import yaml

OUT = Path(__file__).resolve().parents[1] / "tests" / "data" / "moveit_corpus"
TUCKED = {"torso_lift_joint": 0.05, "shoulder_pan_joint": 1.32, "shoulder_lift_joint": 1.4, "upperarm_roll_joint": -0.2,
          "elbow_flex_joint": 1.72, "forearm_roll_joint": 0.0, "wrist_flex_joint": 1.66, "wrist_roll_joint": 0.0}
ALL_JOINTS = ["l_wheel_joint", "r_wheel_joint", "torso_lift_joint", "bellows_joint", "head_pan_joint", "head_tilt_joint",
              "shoulder_pan_joint", "shoulder_lift_joint", "upperarm_roll_joint", "elbow_flex_joint", "forearm_roll_joint",
              "wrist_flex_joint", "wrist_roll_joint", "l_gripper_finger_joint", "r_gripper_finger_joint"]
CAN = (0.12, 0.033)  # MoveIt cylinder dimensions: [height, radius]


def joint_state(values: dict[str, float]) -> dict:
    """A full Fetch joint_state (wheels, head and fingers too, as a robot records it)."""
    return {"name": list(ALL_JOINTS), "position": [float(values.get(n, 0.0)) for n in ALL_JOINTS]}


def box(oid: str, size, xyz, quat=(0, 0, 0, 1)) -> dict:
    return {"id": oid, "header": {"frame_id": "base_link"}, "primitives": [{"type": "box", "dimensions": list(size)}],
            "primitive_poses": [{"position": list(xyz), "orientation": list(quat)}], "operation": 0}


def cylinder(oid: str, height: float, radius: float, xyz) -> dict:
    return {"id": oid, "header": {"frame_id": "base_link"}, "primitives": [{"type": "cylinder", "dimensions": [height, radius]}],
            "primitive_poses": [{"position": list(xyz), "orientation": [0, 0, 0, 1]}], "operation": 0}


def can(oid: str, x: float, y: float, z_support: float) -> dict:
    return cylinder(oid, CAN[0], CAN[1], (x, y, z_support + CAN[0] / 2))


def mesh(oid: str, resource: str, xyz, quat=(0, 0, 0, 1), scale=(1.0, 1.0, 1.0)) -> dict:
    # Robowflex-style mesh reference (as the paper's scenes): resource + dimensions (scale).
    return {"id": oid, "header": {"frame_id": "base_link"}, "meshes": [{"resource": resource, "dimensions": list(scale)}],
            "mesh_poses": [{"position": list(xyz), "orientation": list(quat)}], "operation": 0}


def table(prefix: str, x: float, y: float, size_x: float, size_y: float, height: float, top: float = 0.04) -> list[dict]:
    """A table top with four legs (ids ``<prefix>_top``, ``<prefix>_leg_1..4``)."""
    items = [box(f"{prefix}_top", (size_x, size_y, top), (x, y, height - top / 2))]
    leg = 0.05
    for k, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1)), start=1):
        items.append(box(f"{prefix}_leg_{k}", (leg, leg, height - top),
                         (x + sx * (size_x / 2 - leg), y + sy * (size_y / 2 - leg), (height - top) / 2)))
    return items


def scene(name: str, objects: list[dict], start: dict[str, float]) -> dict:
    return {"name": name, "robot_model_name": "fetch", "robot_state": {"joint_state": joint_state(start)},
            "fixed_frame_transforms": [{"child_frame_id": "base_link", "header": {"frame_id": "base_link"},
                                        "transform": {"translation": [0, 0, 0], "rotation": [0, 0, 0, 1]}}],
            "world": {"collision_objects": objects}, "is_diff": False}


def bookshelf_cans() -> dict:
    """A four-board bookshelf in front of the robot; cans stand at the front of two boards."""
    x, depth, width, height = 0.88, 0.32, 0.9, 1.4
    objs = [box(f"shelf_board_{k}", (depth, width, 0.02), (x, 0.0, z)) for k, z in enumerate((0.30, 0.66, 1.02, 1.38), start=1)]
    objs += [box("shelf_vert_left", (depth, 0.02, height), (x, width / 2 + 0.01, height / 2)),
             box("shelf_vert_right", (depth, 0.02, height), (x, -width / 2 - 0.01, height / 2)),
             box("shelf_back", (0.02, width + 0.04, height), (x + depth / 2 + 0.01, 0.0, height / 2))]
    objs += [can("can_1", 0.78, -0.22, 0.67), can("can_2", 0.78, 0.05, 0.67), can("can_3", 0.80, 0.24, 1.03)]
    return scene("bookshelf_cans", objs, TUCKED)


def can_in_open_box() -> dict:
    """A can inside an open box on a table; the recorded state is all zeros (the arm stretched
    out through the box walls): the real start is in the motion-plan request beside it."""
    objs = table("table", 0.85, 0.0, 0.7, 1.2, 0.72)
    bx, by, side, wall, h = 0.70, 0.0, 0.22, 0.01, 0.08
    objs += [box("open_box_bottom", (side, side, wall), (bx, by, 0.72 + wall / 2)),
             box("open_box_wall_front", (wall, side, h), (bx - side / 2, by, 0.72 + h / 2)),
             box("open_box_wall_back", (wall, side, h), (bx + side / 2, by, 0.72 + h / 2)),
             box("open_box_wall_left", (side, wall, h), (bx, by + side / 2, 0.72 + h / 2)),
             box("open_box_wall_right", (side, wall, h), (bx, by - side / 2, 0.72 + h / 2))]
    objs.append(can("can", bx, by, 0.72 + wall))
    return scene("can_in_open_box", objs, {})


def can_in_open_box_request() -> dict:
    """The motion-plan request that goes with it (MoveIt's MotionPlanRequest: start_state)."""
    start = dict(TUCKED, torso_lift_joint=0.1)
    return {"workspace_parameters": {"header": {"frame_id": "base_link"}, "min_corner": {"x": -1, "y": -1, "z": -1},
                                     "max_corner": {"x": 1, "y": 1, "z": 1}},
            "start_state": {"joint_state": joint_state(start), "is_diff": False},
            "goal_constraints": [], "group_name": "arm_with_torso", "num_planning_attempts": 1,
            "allowed_planning_time": 30.0, "planner_id": "RRTConnectkConfigDefault",
            "max_velocity_scaling_factor": 1.0, "max_acceleration_scaling_factor": 1.0}


def cage_box() -> dict:
    """A small box on a table inside a cage: four posts and a ring of bars on top."""
    objs = table("table", 0.85, 0.0, 0.7, 1.2, 0.72)
    cx, cy, half, top = 0.72, 0.0, 0.16, 0.72 + 0.34
    for k, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1)), start=1):
        objs.append(cylinder(f"cage_post_{k}", 0.34, 0.01, (cx + sx * half, cy + sy * half, 0.72 + 0.17)))
    objs += [box("cage_bar_front", (0.02, 2 * half, 0.02), (cx - half, cy, top)),
             box("cage_bar_back", (0.02, 2 * half, 0.02), (cx + half, cy, top)),
             box("cage_bar_left", (2 * half, 0.02, 0.02), (cx, cy + half, top)),
             box("cage_bar_right", (2 * half, 0.02, 0.02), (cx, cy - half, top))]
    objs.append(box("box", (0.06, 0.06, 0.08), (cx, cy, 0.72 + 0.04)))
    return scene("cage_box", objs, TUCKED)


def table_far_can() -> dict:
    """A wide table with legs; one can near its far edge, 0.85-0.9 m from the base."""
    objs = table("table", 0.80, 0.0, 0.8, 1.2, 0.70)
    objs += [can("Can1", 0.86, -0.12, 0.70), can("Can2", 0.90, 0.28, 0.70)]
    return scene("table_far_can", objs, TUCKED)


def kitchen_meshes() -> dict:
    """A kitchen of mesh furniture: counters (OBJ through a ROS package), a fridge (STL next to
    the scene), an oven and a wall cabinet whose mesh files are missing; cans on the counter."""
    objs = [mesh("counter_front", "package://kitchen_description/meshes/counter.obj", (0.92, 0.0, 0.0)),
            mesh("counter_left", "package://kitchen_description/meshes/counter.obj", (0.3, 0.95, 0.0), (0, 0, 0.7071068, 0.7071068)),
            mesh("fridge", "meshes/fridge.stl", (0.2, -1.0, 0.0)),
            mesh("oven", "package://kitchen_description/meshes/oven.dae", (1.0, -1.0, 0.0)),
            mesh("wall_cabinet", "package://kitchen_description/meshes/wall_cabinet.obj", (1.05, 0.0, 1.6))]
    objs += [can("can_1", 0.72, -0.25, 0.9), can("can_2", 0.75, 0.2, 0.9)]
    return scene("kitchen_meshes", objs, TUCKED)


def noisy_small_shelves() -> dict:
    """Two wall-mounted small shelves with a backing panel; the recorded torso is -1.5e-08
    (sensor noise below the joint's lower limit of 0)."""
    objs = [box("small_shelf_1", (0.3, 0.7, 0.02), (0.82, 0.0, 0.78)),
            box("small_shelf_2", (0.3, 0.7, 0.02), (0.82, 0.0, 1.2)),
            box("shelf_vert", (0.02, 0.7, 0.8), (0.98, 0.0, 1.0))]
    objs += [can("can_a", 0.76, -0.18, 0.79), can("can_b", 0.76, 0.15, 0.79)]
    start = dict(TUCKED, torso_lift_joint=-1.5e-08, shoulder_pan_joint=1.3200001)
    return scene("noisy_small_shelves", objs, start)


def big_box_table() -> dict:
    """A table with a 0.25 m cube named box (wider than the gripper opens) and a small box."""
    objs = table("table", 0.85, 0.0, 0.7, 1.2, 0.72)
    objs += [box("box", (0.25, 0.25, 0.25), (0.80, 0.25, 0.72 + 0.125)),
             box("box_small", (0.06, 0.06, 0.1), (0.70, -0.2, 0.72 + 0.05))]
    return scene("big_box_table", objs, TUCKED)


def box_mesh_obj(sx: float, sy: float, sz: float) -> str:
    """An OBJ box standing on z = 0, centred in x and y."""
    v = [(x, y, z) for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2) for z in (0.0, sz)]
    faces = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    lines = [f"v {x:g} {y:g} {z:g}" for x, y, z in v] + [f"f {a} {b} {c} {d}" for a, b, c, d in faces]
    return "# generated by tools/make_moveit_corpus.py\n" + "\n".join(lines) + "\n"


def box_mesh_stl(sx: float, sy: float, sz: float) -> bytes:
    """The same box as a binary STL (12 triangles)."""
    v = [(x, y, z) for x in (-sx / 2, sx / 2) for y in (-sy / 2, sy / 2) for z in (0.0, sz)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    tris = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    out = bytearray(b"generated by tools/make_moveit_corpus.py".ljust(80, b" ")) + struct.pack("<I", len(tris))
    for tri in tris:
        out += struct.pack("<3f", 0.0, 0.0, 0.0)
        for i in tri:
            out += struct.pack("<3f", *v[i])
        out += struct.pack("<H", 0)
    return bytes(out)


SCENES = {  # file stem -> (builder, natural request, import options)
    "bookshelf_cans": (bookshelf_cans, "pick up a can", {}),
    "can_in_open_box": (can_in_open_box, "pick up a can", {"start_from": "can_in_open_box_request.yaml"}),
    "cage_box": (cage_box, "pick up a box", {}),
    "table_far_can": (table_far_can, "pick up a can", {}),
    "kitchen_meshes": (kitchen_meshes, "pick up a can", {"packages": {"kitchen_description": "kitchen_description"}}),
    "noisy_small_shelves": (noisy_small_shelves, "pick up a can", {}),
    "big_box_table": (big_box_table, "pick up a box", {}),
}


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    dump = lambda data: yaml.safe_dump(data, sort_keys=False, default_flow_style=None, width=120)  # noqa: E731
    manifest = {}
    for stem, (build, request, options) in SCENES.items():
        (OUT / f"{stem}.yaml").write_text(f"# {build.__doc__.split(chr(10))[0]}\n" + dump(build()))
        manifest[stem] = {"file": f"{stem}.yaml", "request": request, **options}
    (OUT / "can_in_open_box_request.yaml").write_text("# MotionPlanRequest for can_in_open_box.yaml\n" + dump(can_in_open_box_request()))
    (OUT / "kitchen_description" / "meshes").mkdir(parents=True, exist_ok=True)
    (OUT / "kitchen_description" / "meshes" / "counter.obj").write_text(box_mesh_obj(0.6, 1.4, 0.9))
    (OUT / "meshes").mkdir(exist_ok=True)
    (OUT / "meshes" / "fridge.stl").write_bytes(box_mesh_stl(0.7, 0.7, 1.8))
    (OUT / "corpus.yaml").write_text("# The MoveIt corpus: scene -> natural request and import options (tools/make_moveit_corpus.py)\n" + dump(manifest))


if __name__ == "__main__":
    main()
