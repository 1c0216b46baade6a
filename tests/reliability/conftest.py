"""Shared paths and helpers for the reliability tests (bad input, faults, stress, determinism)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCENES = REPO / "yaml_scenes"
CORPUS = REPO / "tests" / "corpus"
HAS_DRAKE = importlib.util.find_spec("pydrake") is not None

needs_drake = pytest.mark.skipif(not HAS_DRAKE, reason="pydrake is not installed")


def scene_path(name: str) -> Path:
    """A bundled scene file by name (``parking_1`` -> yaml_scenes/parking_1.yaml)."""
    return SCENES / f"{name}.yaml"

# A small lot whose only free spot lies behind a wall across the whole lot: the spot's goal
# region has valid samples, but no path reaches it (every plan must end in a timeout; the reach
# prior, which proves it at once, is off: these tests need a search that runs to its limit).
WALLED_LOT = """\
name: walled_lot
robot:
  model: car
  start: {car_x: 3.0, car_y: 3.0, car_qz: 0.0}
  limits: {car_x: [0, 30], car_y: [0, 20]}
  weights: {car_qz: 2.0}
obstacles:
  - {id: wall, geometry: {box: [30, 0.3, 2]}, pose: {xyz: [15, 12, 1]}}
objects:
  - {id: spot_1, type: parking_spot, geometry: {box: [5.5, 2.6, 0.05]}, pose: {xyz: [20, 17, 0], rpy: [0, 0, 1.5708]}}
planner: {step_size: 1.0, time_limit: 5, reach_prior: false}
"""


def walled_lot(tmp_path) -> Path:
    p = Path(tmp_path) / "walled_lot.yaml"
    p.write_text(WALLED_LOT)
    return p


def fetch_scene_dict(obstacles=(), objects=()) -> dict:
    """A Fetch scene with the bundled Fetch robot block and the given obstacles and objects."""
    import yaml

    base = yaml.safe_load(scene_path("fetch_put_box_on_table").read_text())
    return {"name": "fetch_fault", "robot": base["robot"], "obstacles": list(obstacles), "objects": list(objects),
            "planner": {"step_size": 0.5, "time_limit": 10.0, "seed": 0, "collision_padding": 0.005}}


def fetch_scene(obstacles=(), objects=()):
    import yaml

    from lazyground.scene import parse_scene

    return parse_scene(yaml.safe_dump(fetch_scene_dict(obstacles, objects)), "fetch_fault.yaml", REPO)


# A table and a can that the Fetch reaches from above in about a second (fetch_cans_1's Can3).
TABLE = {"id": "table", "type": "table", "geometry": {"box": [0.7, 0.7, 0.03]}, "pose": {"xyz": [0.3, 0.75, 0.6525]}}
CAN = {"id": "Can1", "type": "can", "color": "red", "geometry": {"cylinder": {"radius": 0.035, "length": 0.115}},
       "pose": {"xyz": [0.4, 0.5, 0.73]}}
# Walls around the tucked arm (front, sides, lid): the start is free, the can is not reachable.
ARM_CAGE = [
    {"id": "cage_front", "geometry": {"box": [0.02, 0.6, 0.7]}, "pose": {"xyz": [0.2, 0.0, 0.6]}},
    {"id": "cage_left", "geometry": {"box": [0.2, 0.02, 0.7]}, "pose": {"xyz": [0.09, 0.29, 0.6]}},
    {"id": "cage_right", "geometry": {"box": [0.2, 0.02, 0.7]}, "pose": {"xyz": [0.09, -0.29, 0.6]}},
    {"id": "cage_lid", "geometry": {"box": [0.2, 0.6, 0.02]}, "pose": {"xyz": [0.09, 0.0, 0.95]}},
]


def load_tool(name: str):
    """A script in tools/ as a module (registered in sys.modules so dataclasses and pickling work)."""
    import importlib.util
    import sys

    module_name = f"lazyground_tools_{name}"
    if module_name not in sys.modules:
        spec = importlib.util.spec_from_file_location(module_name, REPO / "tools" / f"{name}.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[module_name] = module
        spec.loader.exec_module(module)
    return sys.modules[module_name]
