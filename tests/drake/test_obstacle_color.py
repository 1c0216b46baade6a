"""Issue 34: an obstacle's ``color`` is its colour in the replay (a brown table leg rendered red)."""

import pytest

pytest.importorskip("pydrake")

from lazyground.drake.diagram import environment_items  # noqa: E402
from lazyground.scene import parse_scene  # noqa: E402
from lazyground.scene.colours import COLOR_RGBA, OBSTACLE_SCENE_RGBA  # noqa: E402

SCENE = """\
name: legs
robot: {model: car, start: {car_x: 3, car_y: 3, car_qz: 0}, limits: {car_x: [0, 40], car_y: [0, 40]}}
obstacles:
- {id: leg, geometry: {box: [0.1, 0.1, 0.7]}, pose: {xyz: [10, 10, 0.35]}, color: brown}
- {id: post, geometry: {box: [0.1, 0.1, 0.7]}, pose: {xyz: [12, 10, 0.35]}, color: '#336699'}
- {id: wall, geometry: {box: [0.1, 5, 1]}, pose: {xyz: [14, 10, 0.5]}}
"""


def test_an_obstacle_is_drawn_in_its_colour():
    rgba = {name: tuple(c) for name, _, _, c in environment_items(parse_scene(SCENE, "legs.yaml"))}
    assert rgba["leg"] == COLOR_RGBA["brown"]
    assert rgba["post"] == pytest.approx((0x33 / 255, 0x66 / 255, 0x99 / 255, 1.0))
    assert rgba["wall"] == OBSTACLE_SCENE_RGBA  # no colour: the default
