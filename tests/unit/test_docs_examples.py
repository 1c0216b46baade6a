"""Every YAML example in README.md and docs/*.md loads as its page says (no Drake, well under a second).

A whole scene (``name`` and ``robot``) is parsed as a scene and grounded with the page's first
request where the page gives one; a ``robot:`` block alone is checked against the scene schema;
a ``grasp_types:`` block is added to a small scene and its types grounded; a lexicon block is
merged into the lexicon; a ``robot.yaml`` block is read as one.
"""

import re
import textwrap
from pathlib import Path

import pytest
import yaml

import grounding
from lazyground.robots.defaults import RobotDefaults
from lazyground.scene import RobotSpec, parse_scene
from lazyground.typed_yaml import load_dataclass

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^( *)```yaml\n(.*?)^\1```", re.M | re.S)
# the request each page's whole scenes are tried with (the page's own first command on them)
REQUESTS = {"my_lot": "park", "tiny_lot": "park", "my_table": "pick up a can"}
LOT = """name: lot
robot: {model: car, start: {car_x: 3, car_y: 3, car_qz: 0}, limits: {car_x: [0, 30], car_y: [0, 20]}}
objects:
  - {id: thing_1, type: TYPE, geometry: {cylinder: {radius: 0.03, length: 0.1}}, pose: {xyz: [5, 5, 0.05]}}
"""


def _blocks():
    for page in PAGES:
        text = page.read_text()
        for m in FENCE.finditer(text):
            line = text[: m.start()].count("\n") + 1
            yield pytest.param(textwrap.dedent(m.group(2)), id=f"{page.name}:{line}")


BLOCKS = list(_blocks())


def test_the_docs_have_yaml_examples():
    assert len(BLOCKS) >= 8


@pytest.mark.parametrize("text", BLOCKS)
def test_yaml_example_loads(text):
    data = yaml.safe_load(text)
    assert isinstance(data, dict)
    if {"name", "robot"} <= data.keys():
        scene = parse_scene(text, "example", scene_dir=ROOT)
        if scene.name in REQUESTS:
            assert grounding.ground(REQUESTS[scene.name], scene).interpretations
    elif data.keys() == {"robot"}:
        load_dataclass(data["robot"], RobotSpec, "robot")
    elif data.keys() == {"grasp_types"}:
        for name, definition in data["grasp_types"].items():
            scene = parse_scene(LOT.replace("TYPE", name) + text, "example", scene_dir=ROOT)
            if "pick" in definition:
                assert grounding.ground(f"pick up the {name}", scene).interpretations
    elif data.keys() <= {"nouns", "verbs", "colours"}:
        grounding.load_lexicon(extra=data)
    elif "model" in data:
        load_dataclass(data, RobotDefaults, "robot.yaml")
    else:
        pytest.fail(f"a YAML example this test does not know how to load: keys {sorted(data)}")


ROW = re.compile(r"^\| [^|]+ \| `([^`]+)` \| (\w+) \| ((?:`[^`]+` ?)+) \|$", re.M)
CONSTRUCTIONS = [pytest.param(m.group(1), m.group(2), set(m.group(3).strip("` ").split()), id=m.group(1))
                 for m in ROW.finditer((ROOT / "docs" / "requests.md").read_text())]


def test_the_requests_page_has_a_construction_table():
    assert len(CONSTRUCTIONS) >= 20


@pytest.mark.parametrize("request_text, scene_name, expected", CONSTRUCTIONS)
def test_construction_example_grounds_as_the_page_says(request_text, scene_name, expected):
    from lazyground.scene import load_scene

    scene = load_scene(ROOT / "yaml_scenes" / f"{scene_name}.yaml")
    assert {i.id for i in grounding.ground(request_text, scene).interpretations} == expected
