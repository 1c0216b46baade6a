"""Plain-numpy helpers that turn a PlanResult into things to draw."""

from __future__ import annotations

import numpy as np

from lazyground.geometry import wrap_angle
from lazyground.typed_yaml import SceneError

PLANAR_SUFFIXES = ("_x", "_y", "_qz")  # Drake's PlanarJoint position names


def planar_indices(joint_names) -> tuple[int, int, int]:
    """Indices of (x, y, heading) in the planned coordinates of a planar robot.

    Raises:
        SceneError: the robot is not planar (the top-down plots need x, y, heading).
    """
    names = list(joint_names)
    out = []
    for suffix in PLANAR_SUFFIXES:
        hits = [i for i, n in enumerate(names) if n.endswith(suffix)]
        if len(hits) != 1:
            raise SceneError(f"top-down parking plots need a planar robot (x, y, heading); this one plans {', '.join(names)}")
        out.append(hits[0])
    return tuple(out)


def tree_edges(parents: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(child, parent) index arrays of every edge of a tree given by its parent array."""
    parents = np.asarray(parents, int)
    child = np.flatnonzero(parents >= 0)
    return child, parents[child]


def resample_path(path: np.ndarray, n: int, wrap=None) -> np.ndarray:
    """``n`` configurations evenly spaced by (unweighted) arc length along ``path``.

    ``wrap`` is a boolean mask of angle coordinates, interpolated along the shorter arc.
    """
    path = np.asarray(path, float)
    if len(path) < 2 or n < 2:
        return np.repeat(path[:1], max(n, 1), axis=0)
    wrap = np.zeros(path.shape[1], bool) if wrap is None else np.asarray(wrap, bool)
    steps = np.diff(path, axis=0)
    steps[:, wrap] = wrap_angle(steps[:, wrap])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(steps, axis=1))])
    if s[-1] <= 0:
        return np.repeat(path[:1], n, axis=0)
    t = np.linspace(0.0, s[-1], n)
    k = np.clip(np.searchsorted(s, t, side="right") - 1, 0, len(path) - 2)
    frac = ((t - s[k]) / np.maximum(s[k + 1] - s[k], 1e-12))[:, None]
    out = path[k] + frac * steps[k]
    out[:, wrap] = wrap_angle(out[:, wrap])
    return out


def rect_corners(x: float, y: float, heading: float, length: float, width: float) -> np.ndarray:
    """The 4 corners (4, 2) of a length x width rectangle centred at (x, y), rotated by heading."""
    c, s = np.cos(heading), np.sin(heading)
    local = np.array([[1, 1], [-1, 1], [-1, -1], [1, -1]]) * [length / 2, width / 2]
    return local @ np.array([[c, s], [-s, c]]) + [x, y]


def frames_in_time(trajectory, fps: float) -> np.ndarray:
    """Configurations of a timed trajectory every 1 / ``fps`` s (and at its end): a replay at real speed.

    The trajectory's samples are interpolated linearly (its ``q`` is continuous: wrapping
    coordinates are unwrapped).
    """
    t, q = trajectory.t, trajectory.q
    times = np.arange(0.0, t[-1], 1.0 / fps)
    times = np.append(times, t[-1]) if not len(times) or t[-1] - times[-1] > 1e-9 else times
    return np.stack([np.interp(times, t, q[:, j]) for j in range(q.shape[1])], axis=1)
