"""The plain-numpy helpers behind the drawings."""

import numpy as np
import pytest

from lazyground.typed_yaml import SceneError
from lazyground.viz.style import weight_rgba
from lazyground.viz.trace import planar_indices, rect_corners, resample_path, tree_edges


def test_weight_colours_run_red_yellow_green():
    red, yellow, green = weight_rgba(0.0), weight_rgba(0.5), weight_rgba(1.0)
    assert red[0] > 0.8 and red[1] < 0.2
    assert yellow[0] > 0.9 and yellow[1] > 0.7
    assert green[1] > 0.6 and green[0] < 0.2
    assert weight_rgba(-1.0) == red and weight_rgba(2.0) == green
    assert weight_rgba(0.3, alpha=0.5)[3] == 0.5


def test_planar_indices():
    assert planar_indices(("car_x", "car_y", "car_qz")) == (0, 1, 2)
    assert planar_indices(("car_qz", "car_y", "car_x")) == (2, 1, 0)
    with pytest.raises(SceneError):
        planar_indices(("shoulder", "elbow"))


def test_tree_edges_skip_the_root():
    child, parent = tree_edges(np.array([-1, 0, 0, 2]))
    assert child.tolist() == [1, 2, 3] and parent.tolist() == [0, 0, 2]


def test_resample_path_keeps_ends_and_spacing():
    path = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 3.0]])
    out = resample_path(path, 9)
    assert np.allclose(out[0], path[0]) and np.allclose(out[-1], path[-1])
    steps = np.linalg.norm(np.diff(out, axis=0), axis=1)
    assert np.allclose(steps, 0.5)  # arc length 4, 8 equal pieces


def test_resample_path_turns_angles_the_short_way():
    path = np.array([[0.0, 3.0], [0.0, -3.0]])  # heading 3 -> -3 crosses pi, 0.28 rad
    out = resample_path(path, 5, wrap=[False, True])
    assert np.all(np.abs(out[:, 1]) > 2.9)


def test_rect_corners_rotate():
    c = rect_corners(1.0, 2.0, np.pi / 2, 4.0, 2.0)
    assert np.allclose(c.min(axis=0), [0.0, 0.0]) and np.allclose(c.max(axis=0), [2.0, 4.0])
