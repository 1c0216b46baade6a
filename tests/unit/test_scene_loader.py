"""The strict scene loader: good scenes load, every malformed one fails with one line."""

import textwrap
from pathlib import Path

import pytest
import yaml

from lazyground.scene import SceneError, load_scene, parse_scene

ROOT = Path(__file__).resolve().parents[2]
CORPUS = yaml.safe_load((ROOT / "tests/corpus/bad_scenes.yaml").read_text())
CAR = "robot: {model: car, start: {car_x: 3, car_y: 3, car_qz: 0}, limits: {car_x: [0, 40], car_y: [0, 40]}}\n"


def test_corpus_is_large_enough():
    assert len(CORPUS) >= 30
    assert len({c["name"] for c in CORPUS}) == len(CORPUS)


@pytest.mark.parametrize("case", CORPUS, ids=[c["name"] for c in CORPUS])
def test_bad_scene_is_rejected_with_one_line(case):
    text = case["scene"].replace("{CAR}", CAR)
    with pytest.raises(SceneError) as info:
        parse_scene(text, "bad.yaml", ROOT)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith("bad.yaml: ")
    assert case["error"] in message


def test_a_folder_is_not_a_missing_file(tmp_path):
    # audit8: "plan some_folder park" said "some_folder: no such scene file (bundled scenes: ...)"
    folder = tmp_path / "scenes.yaml"
    folder.mkdir()
    with pytest.raises(SceneError, match=r"scenes\.yaml: is a folder, not a scene file$"):
        load_scene(folder)


def test_minimal_scene_loads_with_defaults():
    scene = parse_scene("name: x\n" + CAR, "ok.yaml", ROOT)
    assert scene.robot.model.endswith("models/car/car.urdf")
    assert scene.planner.goal_bias == 0.05 and scene.planner.strategy == "reward-penalty"
    assert scene.objects == () and scene.expect == ()


def test_full_object_record():
    text = textwrap.dedent(
        """\
        name: kitchen
        robot: {model: car, start: {}}
        objects:
          - id: can_1
            type: can
            color: red
            size: small
            geometry: {cylinder: {radius: 0.03, length: 0.12}}
            pose: {xyz: [1, 2, 0.8], rpy: [0, 0, 1.57]}
            attributes: {brand: fizz}
          - id: spot
            type: parking_spot
            geometry: {box: [5.5, 2.6, 0.05]}
            occupied: true
        """
    )
    scene = parse_scene(text, "k.yaml", ROOT)
    can = scene.object("can_1")
    assert can.color == "red" and can.pose.xyz == (1.0, 2.0, 0.8) and can.attributes == {"brand": "fizz"}
    assert can.collides and not scene.object("spot").collides and scene.object("spot").occupied


def test_bundled_scenes_load():
    paths = sorted((ROOT / "yaml_scenes").glob("*.yaml"))
    assert len(paths) >= 2
    for p in paths:
        assert load_scene(p).expect, p


def test_missing_file(tmp_path):
    with pytest.raises(SceneError, match="no such scene file"):
        load_scene(tmp_path / "nope.yaml")


def test_huge_file_is_refused_without_parsing(tmp_path):
    big = tmp_path / "big.yaml"
    with big.open("w") as f:
        f.write("name: x\n# " + "x" * (50 * 1024 * 1024) + "\n")
    with pytest.raises(SceneError, match=r"file is 52 MB; scenes are limited to 5 MiB"):
        load_scene(big)


def test_binary_file(tmp_path):
    p = tmp_path / "bin.yaml"
    p.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(SceneError, match="not a UTF-8 text file"):
        load_scene(p)


def test_model_path_relative_to_scene(tmp_path):
    (tmp_path / "m").mkdir()
    (tmp_path / "m/r.urdf").write_text((ROOT / "models/car/car.urdf").read_text())
    scene_file = tmp_path / "s.yaml"
    scene_file.write_text("name: x\nrobot: {model: m/r.urdf, start: {}}\n")
    assert load_scene(scene_file).robot.model == str((tmp_path / "m/r.urdf").resolve())


def test_per_algorithm_settings_apply_only_to_their_algorithm():
    from lazyground.api import planner_settings

    text = "name: x\n" + CAR + (
        "planner: {algorithm: bidirectional, step_size: 0.5, edge_resolution: 0.05, goal_extension: extend,\n"
        "  per_algorithm: {rrt: {step_size: 2.65, goal_extension: partial}}}\n"
    )
    scene = parse_scene(text, "ok.yaml", ROOT)
    two = planner_settings(scene)  # the scene's own algorithm: no per-algorithm settings for it
    assert (two.algorithm, two.step_size, two.resolution, two.goal_extension) == ("bidirectional", 0.5, 0.05, "extend")
    one = planner_settings(scene, algorithm="rrt")
    assert (one.step_size, one.resolution, one.goal_extension) == (2.65, 0.05, "partial")
    explicit = planner_settings(scene, algorithm="rrt", step_size=1.0, goal_extension="connect")
    assert (explicit.step_size, explicit.goal_extension) == (1.0, "connect")  # the caller's word is last


def test_fast_yaml_parser_reads_every_bundled_scene_as_pyyaml_does():
    # #31: scenes parse with libyaml (~10x faster than PyYAML's pure-Python parser); same data, same errors
    from lazyground import typed_yaml
    from lazyground.bundled import bundled_scene, scene_names

    if typed_yaml._FAST_LOADER is None:
        pytest.skip("PyYAML built without libyaml")
    for name in scene_names():
        text = bundled_scene(name).read_text()
        assert len(text) <= typed_yaml.FAST_YAML_MAX_CHARS
        fast = list(yaml.load_all(text, Loader=typed_yaml._FAST_LOADER))
        assert fast == list(yaml.load_all(text, Loader=typed_yaml._UniqueKeyLoader)), name


def test_an_error_reads_the_same_with_the_fast_parser():
    from lazyground import typed_yaml

    text = "objects: []\nplanner: {seed: 1}\nobjects: [a]\n"
    messages = []
    for fast in (typed_yaml.FAST_YAML_MAX_CHARS, -1):
        old, typed_yaml.FAST_YAML_MAX_CHARS = typed_yaml.FAST_YAML_MAX_CHARS, fast
        try:
            with pytest.raises(yaml.YAMLError) as info:
                typed_yaml.load_yaml(text)
        finally:
            typed_yaml.FAST_YAML_MAX_CHARS = old
        messages.append(str(info.value))
    assert messages[0] == messages[1]
    assert "duplicate key 'objects' (first at line 1)" in messages[0] and "line 3" in messages[0]


def test_deep_nesting_is_refused_not_a_crash():
    # libyaml composes nested collections in C without Python's recursion limit (100k levels overflowed the
    # stack): long text keeps PyYAML's parser, which stops at the recursion limit
    text = "a: " + "[" * 100_000 + "]" * 100_000 + "\n"
    with pytest.raises(SceneError, match="nesting too deep"):
        parse_scene(text, "deep.yaml")


def test_a_scene_file_is_parsed_once_until_it_changes(tmp_path, monkeypatch):
    # #31: api.plan on a path loads the file every call; the same text gives the same Scene without parsing it again
    from lazyground.scene import loader

    path = tmp_path / "s.yaml"
    path.write_text("name: x\n" + CAR)
    calls = []
    parse = loader.parse_scene
    monkeypatch.setattr(loader, "parse_scene", lambda *a, **k: calls.append(1) or parse(*a, **k))
    first = load_scene(path)
    assert load_scene(path) is first and len(calls) == 1
    path.write_text("name: x\n" + CAR + "planner: {seed: 4}\n")
    changed = load_scene(path)
    assert len(calls) == 2 and changed.planner.seed == 4
    path.write_text("name: x\n" + CAR + "planner: {seed: [}\n")
    with pytest.raises(SceneError, match="YAML syntax error"):
        load_scene(path)
