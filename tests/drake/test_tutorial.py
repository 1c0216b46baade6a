"""#20: the tutorial's scenes load, ground as the text says and plan (docs/tutorial.md)."""

from __future__ import annotations

import re

import pytest

pytest.importorskip("pydrake")

import grounding  # noqa: E402
from lazyground import api  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning.rrt import path_is_valid  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from tests.counts import BY_COUNTS  # noqa: E402
from tests.unit.test_grounding import REPO  # noqa: E402

TEXT = (REPO / "docs" / "tutorial.md").read_text()
BLOCKS = dict(zip(("my_lot", "my_table"), re.findall(r"```yaml\n(.*?)```", TEXT, re.S)))


@pytest.fixture(scope="module")
def scenes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("tutorial")
    out = {}
    for name, text in BLOCKS.items():
        (folder / f"{name}.yaml").write_text(text)
        out[name] = load_scene(folder / f"{name}.yaml")
    return out


@pytest.mark.parametrize("name,request_text,expected", [
    ("my_lot", "park", {"park:spot_a1", "park:spot_a3"}),
    ("my_lot", "park in spot a3", {"park:spot_a3"}),
    ("my_lot", "park in the closest spot", {"park:spot_a1"}),
    ("my_lot", "park in the farthest spot", {"park:spot_a3"}),
    ("my_table", "pick up a can", {"pick:can_red", "pick:can_blue"}),
    ("my_table", "pick up the red can", {"pick:can_red"}),
    ("my_table", "grab the can on the left", {"pick:can_red"}),
])
def test_tutorial_requests_ground_as_documented(scenes, name, request_text, expected):
    assert f'"{request_text}"' in TEXT
    assert {i.id for i in grounding.ground(request_text, scenes[name]).interpretations} == expected


@pytest.mark.parametrize("name,request_text", [("my_lot", "park"), ("my_table", "pick up the red can")])
def test_tutorial_scenes_plan(scenes, name, request_text):
    world = DrakeWorld(scenes[name])
    report = api.plan(scenes[name], request_text, seed=0, world=world, **BY_COUNTS)
    res = report.result
    assert res.solved, res.message
    assert path_is_valid(world.space, world, res.path, report.settings.planner.resolution / 10) == -1
