"""MoveIt import fuzzing (#15): mutated planning scenes convert or raise a one-line SceneError.

Mutations of a corpus scene (a key deleted, a value replaced by another type, a number made
negative, NaN or huge) go through ``convert_moveit``; anything but a scene mapping or a
SceneError is a bug. Hypothesis runs derandomized, so CI sees the same examples every time.
"""

from __future__ import annotations

import copy

import yaml
from hypothesis import HealthCheck, example, given, settings, strategies as st

from lazyground.bench.moveit_corpus import CORPUS
from lazyground.moveit import convert_moveit
from lazyground.scene import SceneError

FUZZ = settings(max_examples=300, deadline=None, derandomize=True, suppress_health_check=list(HealthCheck))
BASE = yaml.safe_load((CORPUS / "kitchen_meshes.yaml").read_text())
VALUES = st.one_of(st.none(), st.booleans(), st.integers(-3, 3), st.floats(allow_nan=True, allow_infinity=True),
                   st.text(max_size=5), st.lists(st.integers(0, 2), max_size=4), st.dictionaries(st.text(max_size=3), st.integers(), max_size=2))


def _paths(node, prefix=()):
    yield prefix
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, child in items:
        yield from _paths(child, prefix + (key,))


PATHS = [p for p in _paths(BASE) if p]


@FUZZ
@given(st.lists(st.tuples(st.sampled_from(PATHS), st.booleans(), VALUES), min_size=1, max_size=3))
@example(mutations=[(("robot_state", "joint_state", "position", 2), False, 1)])  # a start outside the joint limits
def test_mutated_scenes_convert_or_fail_in_one_line(mutations):
    data = copy.deepcopy(BASE)
    for path, delete, value in mutations:
        parent = data
        try:
            for key in path[:-1]:
                parent = parent[key]
            if delete and isinstance(parent, dict):
                parent.pop(path[-1], None)
            else:
                parent[path[-1]] = value
        except (KeyError, IndexError, TypeError):
            continue
    try:
        scene, _ = convert_moveit(data, "fuzz.yaml", scene_dir=CORPUS)
    except SceneError as exc:
        assert "\n" not in str(exc) and str(exc).startswith("fuzz.yaml: ")
    else:
        assert scene["obstacles"] or scene["objects"]
