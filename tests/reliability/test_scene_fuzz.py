"""Scene fuzzing: random YAML trees and mutated valid scenes never escape as anything but SceneError.

``parse_scene`` gets random YAML trees, random text and mutations of valid
scenes (a key deleted, a type changed, unknown keys, negative, NaN/inf and
huge numbers, deep nesting, duplicated list items); it must return a Scene or
raise a one-line SceneError. The few mutated scenes that load are built into a
:class:`DrakeWorld`, which may only raise SceneError too. Hypothesis runs
derandomized, so CI sees the same examples every time.
"""

from __future__ import annotations

import copy
import math
import re

import pytest
import yaml
from hypothesis import HealthCheck, given, settings, strategies as st

from lazyground.scene import Scene, SceneError, parse_scene
from tests.reliability.conftest import REPO, needs_drake, scene_path

FUZZ = settings(max_examples=200, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
DRAKE_FUZZ = settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))

SCHEMA_KEYS = [
    "name", "robot", "model", "start", "base", "base_link", "planned_joints", "limits", "weights", "end_effector",
    "obstacles", "objects", "id", "type", "geometry", "box", "cylinder", "sphere", "radius", "length", "pose", "xyz",
    "rpy", "planner", "strategy", "goal_bias", "step_size", "time_limit", "seed", "expect", "request", "grasp_types",
    "occupied", "collision", "attributes", "color", "size", "description",
]
HUGE = [10**400, -(10**400), 2**63, 1e308, -1e308, float("inf"), float("-inf"), float("nan"), 1e-320]
SCALARS = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from(HUGE),
    st.text(max_size=12),
    st.sampled_from(["car", "fetch", "can", "parking_spot", "reward-penalty", "", " ", "base_link", "car_x"]),
)
KEYS = st.one_of(st.sampled_from(SCHEMA_KEYS), st.text(max_size=8), st.integers(-3, 3))
TREES = st.recursive(
    SCALARS,
    lambda children: st.lists(children, max_size=4) | st.dictionaries(KEYS, children, max_size=5),
    max_leaves=25,
)

CAR_SCENE = {
    "name": "fuzz_car",
    "robot": {"model": "car", "start": {"car_x": 3.0, "car_y": 3.0, "car_qz": 0.0},
              "limits": {"car_x": [0, 40], "car_y": [0, 40]}, "weights": {"car_qz": 2.0}},
    "obstacles": [{"id": "pillar", "geometry": {"cylinder": {"radius": 0.3, "length": 3}}, "pose": {"xyz": [10, 3, 1.5]}}],
    "objects": [
        {"id": "spot_1", "type": "parking_spot", "geometry": {"box": [5.5, 2.6, 0.05]}, "pose": {"xyz": [20, 17, 0], "rpy": [0, 0, 1.5708]}},
        {"id": "spot_2", "type": "parking_spot", "occupied": True, "geometry": {"box": [5.5, 2.6, 0.05]}, "pose": {"xyz": [25, 17, 0]}},
    ],
    "planner": {"step_size": 1.0, "time_limit": 5, "seed": 3},
    "expect": [{"request": "park", "seeds": 2}],
}


def _bundled(name: str) -> dict:
    return yaml.safe_load(scene_path(name).read_text())


BASES = {"car": CAR_SCENE, "parking_1": _bundled("parking_1"), "fetch": _bundled("fetch_put_box_on_table")}


def check_parse(text: str) -> Scene | None:
    """parse_scene's contract: a Scene, or a SceneError with one non-empty line."""
    try:
        return parse_scene(text, "fuzz.yaml", REPO)
    except SceneError as exc:
        message = str(exc)
        assert message.startswith("fuzz.yaml: ") and "\n" not in message, message
        return None


def dump(tree) -> str:
    return yaml.safe_dump(tree, allow_unicode=True, sort_keys=False)


def paths(tree, prefix=()):
    """Every (path, value) in a tree; a path is a tuple of keys and indices."""
    yield prefix, tree
    if isinstance(tree, dict):
        for k, v in tree.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(tree, list):
        for i, v in enumerate(tree):
            yield from paths(v, prefix + (i,))


def _parent(tree, path):
    node = tree
    for k in path[:-1]:
        node = node[k]
    return node


def nest(value, depth: int):
    for _ in range(depth):
        value = [value]
    return value


MUTATIONS = ("delete", "retype", "unknown_key", "negate", "nan_inf", "huge", "zero", "nest", "duplicate")


def mutate(tree, op: str, path: tuple, data) -> None:
    """Apply one mutation in place at ``path`` (the root when a mutation needs a parent and path is ())."""
    node = _parent(tree, path) if path else None
    key = path[-1] if path else None
    value = node[key] if path else tree
    if op == "delete" and path:
        del node[key]
    elif op == "retype" and path:
        node[key] = data.draw(st.one_of(SCALARS, st.just([]), st.just({}), st.just([1, 2, 3]), st.just({"x": 1})), label="new")
    elif op == "unknown_key":
        target = value if isinstance(value, dict) else tree
        target[data.draw(st.sampled_from(["colour", "speed", "mass", "", "0", "robot_", "X"]), label="key")] = 1
    elif op == "negate" and path and isinstance(value, (int, float)) and not isinstance(value, bool):
        node[key] = -value if value else -1
    elif op == "nan_inf" and path:
        node[key] = data.draw(st.sampled_from([float("nan"), float("inf"), float("-inf")]), label="special")
    elif op == "huge" and path:
        node[key] = data.draw(st.sampled_from(HUGE), label="huge")
    elif op == "zero" and path:
        node[key] = 0
    elif op == "nest" and path:
        node[key] = nest(value, data.draw(st.sampled_from([1, 3, 50]), label="depth"))
    elif op == "duplicate" and isinstance(value, list) and value:
        value.append(copy.deepcopy(value[0]))


@st.composite
def mutated_scenes(draw, bases=tuple(BASES)):
    tree = copy.deepcopy(BASES[draw(st.sampled_from(bases), label="base")])
    data = _Draw(draw)
    for _ in range(draw(st.integers(1, 3), label="mutations")):
        all_paths = [p for p, _ in paths(tree)]
        path = all_paths[draw(st.integers(0, len(all_paths) - 1), label="where")]
        mutate(tree, draw(st.sampled_from(MUTATIONS), label="op"), path, data)
    return tree


class _Draw:
    """Adapts a composite's ``draw`` to the ``data.draw(strategy, label=...)`` call mutate() uses."""

    def __init__(self, draw):
        self._draw = draw

    def draw(self, strategy, label=None):
        return self._draw(strategy, label=label)


# --- the loader ---------------------------------------------------------------------------------

@FUZZ
@given(tree=TREES)
def test_random_trees(tree):
    check_parse(dump(tree))


@FUZZ
@given(tree=st.dictionaries(st.sampled_from(SCHEMA_KEYS[:12] + ["planner", "objects", "obstacles"]), TREES, min_size=1, max_size=6))
def test_random_trees_with_schema_keys(tree):
    check_parse(dump(tree))


@FUZZ
@given(text=st.text(max_size=200))
def test_random_text(text):
    check_parse(text)


@FUZZ
@given(tree=mutated_scenes())
def test_mutated_scenes(tree):
    scene = check_parse(dump(tree))
    if scene is not None:  # what loads is well formed where the schema promises it
        for obj in scene.obstacles + scene.objects:
            assert all(math.isfinite(v) for v in obj.pose.xyz + obj.pose.rpy)
            assert all(v > 0 and math.isfinite(v) for v in obj.geometry.half_extents())
        assert 0 <= scene.planner.goal_bias <= 1 and scene.planner.time_limit > 0


@pytest.mark.parametrize("depth", [10, 999, 5000, 100_000])
def test_deep_nesting_is_one_line(depth):
    for text in ("[" * depth + "]" * depth, "name: x\nrobot: " + "{a: " * depth + "1" + "}" * depth):
        scene = check_parse(text)
        assert scene is None


@pytest.mark.parametrize(
    "edit,fragment",
    [  # regressions: each of these once escaped as another exception type
        ({"planner": {"step_size": 10**400}}, "fuzz.yaml: planner.step_size: number out of range"),
        ({"planner": {"seed": -(10**400)}}, "fuzz.yaml: planner.seed: number out of range"),
        ({"obstacles": [{"id": "w", "geometry": {"box": [10**400, 1, 1]}}]}, "obstacles[0].geometry.box[0]: number out of range"),
        ({"grasp_types": {"can": 3}}, "fuzz.yaml: grasp_types.can: expected a mapping, got number 3"),
        ({"grasp_types": {"can": {"pick": [{"template": "top", "depth": [0, 0.02]}]}}}, None),  # raised TypeError
    ],
)
def test_loader_regressions(edit, fragment):
    tree = copy.deepcopy(CAR_SCENE) | edit
    scene = check_parse(dump(tree))
    if fragment is None:
        assert scene is not None and scene.grasp_types == edit["grasp_types"]
        return
    with pytest.raises(SceneError, match=re.escape(fragment)):
        parse_scene(dump(tree), "fuzz.yaml", REPO)


def test_mutations_are_not_all_rejected():
    """Guard against a fuzzer that only ever feeds garbage: unknown keys are rejected, a retyped
    description still loads, and the unmutated bases load."""
    for name, base in BASES.items():
        assert check_parse(dump(base)) is not None, name
    bad = copy.deepcopy(CAR_SCENE)
    bad["robot"]["speed"] = 3
    assert check_parse(dump(bad)) is None
    ok = copy.deepcopy(CAR_SCENE)
    ok["description"] = "still fine"
    assert check_parse(dump(ok)) is not None


# --- the Drake world: only SceneError -----------------------------------------------------------

POSITIONS = {"car": ["car_x", "car_y", "car_qz"], "fetch": ["torso_lift_joint", "shoulder_pan_joint", "elbow_flex_joint", "wrist_roll_joint", "head_pan_joint", "l_gripper_finger_joint"]}
JOINTS = {"car": ["car"], "fetch": ["torso_lift_joint", "shoulder_pan_joint", "elbow_flex_joint", "head_pan_joint", "r_wheel_joint"]}
LINKS = ["base_link", "car_body", "gripper_link", "torso_lift_link", "world", "nope"]
NUMBERS = st.one_of(st.floats(-50, 50), st.sampled_from([0.0, -1e30, 1e30, 1e-12, math.pi, 2 * math.pi]))


@st.composite
def robot_mutations(draw):
    """Valid-typed but semantically odd robot blocks and geometry: these get past the loader to Drake."""
    base = draw(st.sampled_from(["car", "fetch"]), label="base")
    tree = copy.deepcopy(BASES[base])
    robot, names = tree["robot"], POSITIONS[base]
    for _ in range(draw(st.integers(1, 3), label="edits")):
        edit = draw(st.sampled_from(["start", "drop_start", "limits", "weights", "planned", "base", "base_link", "size", "pose"]), label="edit")
        if edit == "start":
            robot["start"][draw(st.sampled_from(names))] = draw(NUMBERS)
        elif edit == "drop_start" and robot["start"]:
            robot["start"].pop(draw(st.sampled_from(sorted(robot["start"]))))
        elif edit == "limits":
            robot.setdefault("limits", {})[draw(st.sampled_from(names))] = sorted(draw(st.lists(NUMBERS, min_size=2, max_size=2)))
        elif edit == "weights":
            robot.setdefault("weights", {})[draw(st.sampled_from(names))] = draw(st.floats(1e-6, 1e6))
        elif edit == "planned":
            robot["planned_joints"] = draw(st.lists(st.sampled_from(JOINTS[base] + ["nope"]), max_size=3, unique=True))
        elif edit == "base":
            robot["base"] = {"xyz": draw(st.lists(NUMBERS, min_size=3, max_size=3))}
        elif edit == "base_link":
            robot["base_link"] = draw(st.sampled_from(LINKS))
        elif edit in ("size", "pose") and tree.get("objects"):
            obj = tree["objects"][draw(st.integers(0, len(tree["objects"]) - 1))]
            if edit == "size":
                obj["geometry"] = {"box": [draw(st.sampled_from([1e-9, 1e-3, 1.0, 1e6])) for _ in range(3)]}
            else:
                obj["pose"] = {"xyz": draw(st.lists(NUMBERS, min_size=3, max_size=3)), "rpy": draw(st.lists(NUMBERS, min_size=3, max_size=3))}
    return tree


def check_world(scene: Scene) -> None:
    from lazyground.drake.world import DrakeWorld

    try:
        world = DrakeWorld(scene, visual=False)
    except SceneError as exc:
        assert "\n" not in str(exc)
        return
    assert world.space.dim >= 1 and world.space.within_bounds(world.start)


@needs_drake
@DRAKE_FUZZ
@given(tree=st.one_of(robot_mutations(), mutated_scenes(bases=("car", "fetch"))))
def test_mutated_scenes_build_or_raise_scene_error(tree):
    scene = check_parse(dump(tree))
    if scene is not None:
        check_world(scene)


@needs_drake
@pytest.mark.parametrize(
    "robot_edit,fragment",
    [
        ({"base": {"xyz": [0, 0, 0]}, "base_link": "base_link"}, "robot.base_link: no link 'base_link' in the model"),
        ({"base": {"xyz": [0, 0, 0]}}, "robot.base: cannot weld 'car_body' to the world"),  # robot.yaml's base_link
        ({"base": {"xyz": [0, 0, 0]}, "base_link": "car_body"}, "robot.base: cannot weld 'car_body' to the world"),
        ({"planned_joints": []}, "robot: nothing to plan"),
        ({"planned_joints": ["steering"]}, "robot.planned_joints: no joint 'steering' in the model"),
        ({"start": {"car_x": 3.0, "car_y": 3.0, "car_z": 1.0}}, "robot: no position 'car_z' in the model"),
        ({"start": {"car_x": 99.0, "car_y": 3.0}}, "robot.start.car_x: 99 is outside the joint limits [0, 40]"),
        ({"limits": {"car_x": [0, 40]}}, "robot.limits: position 'car_y' is unbounded"),
        ({"model": "models/fetch/../car/car.urdf", "planned_joints": ["car"], "limits": {"car_x": [0, 40], "car_y": [0, 40]}}, None),
    ],
)
def test_drake_level_faults(robot_edit, fragment):
    tree = copy.deepcopy(CAR_SCENE)
    tree["robot"].update(robot_edit)
    scene = check_parse(dump(tree))
    assert scene is not None
    from lazyground.drake.world import DrakeWorld

    if fragment is None:
        assert DrakeWorld(scene, visual=False).space.dim == 3
        return
    with pytest.raises(SceneError) as info:
        DrakeWorld(scene, visual=False)
    assert fragment in str(info.value) and "\n" not in str(info.value)
