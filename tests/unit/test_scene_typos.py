"""Typos in scene files get suggestions, with the file and line (#29)."""

from __future__ import annotations

import pytest

from grounding import GroundingError, ground
from lazyground.scene import SceneError, load_scene

HEAD = "name: x\nrobot: {model: car, start: {car_x: 1, car_y: 1, car_qz: 0}}\n"


def _write(tmp_path, text):
    path = tmp_path / "scene.yaml"
    path.write_text(text)
    return path


def test_a_misspelt_key_names_the_key_it_meant_and_its_line(tmp_path):
    path = _write(tmp_path, HEAD + "planer: {}\nobjects: []\n")
    with pytest.raises(SceneError) as info:
        load_scene(path)
    msg = str(info.value)
    assert msg.startswith(f"{path}: planer: unknown key; did you mean 'planner'?") and msg.endswith("(line 3)"), msg


def test_a_nested_misspelt_key(tmp_path):
    text = HEAD + "objects:\n- id: a\n  type: can\n  geometry: {box: [0.1, 0.1, 0.1]}\n  pose: {xyz: [5, 5, 0.05], rpx: [0, 0, 0]}\n"
    with pytest.raises(SceneError) as info:
        load_scene(_write(tmp_path, text))
    msg = str(info.value)
    assert "objects[0].pose.rpx: unknown key; did you mean 'rpy'?" in msg and msg.endswith("(line 7)"), msg


def test_a_misspelt_type_is_matched_through_the_words_for_it(tmp_path):
    path = _write(tmp_path, HEAD + "objects:\n- {id: a, type: parking_spot, geometry: {box: [5, 2.5, 0.05]}, pose: {xyz: [5, 5, 0]}}\n"
                                   "- {id: b, type: mugg, geometry: {box: [0.1, 0.1, 0.1]}, pose: {xyz: [9, 9, 0.05]}}\n")
    with pytest.raises(GroundingError) as info:
        ground("park", load_scene(path))
    msg = str(info.value)
    assert msg.startswith("object 'b': unknown type 'mugg'; did you mean 'cup'?") and msg.endswith(f"({path} line 5)"), msg
