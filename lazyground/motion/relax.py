"""Vertex relaxation: pull a path's interior waypoints straight between their neighbours (no Drake).

Shortcuts end where a segment from one point of the path to another hits an obstacle, so a
shortcut path bends at points left where the raw path happened to put them. Relaxation moves
each interior waypoint towards the point of the segment between its neighbours nearest to
it (there the two adjacent segments are as short as they can be: the sum of the distances
to the neighbours is convex, so every step towards it gains), a shorter step when the full
one collides, while both adjacent segments stay free. Long segments are first cut into
pieces so that the path can bend around an obstacle in more places than the corners it had.
This is the elastic-band idea (Quinlan and Khatib, "Elastic bands", ICRA 1993) with the
collision checker in place of repulsive forces.
"""

from __future__ import annotations

import numpy as np

from lazyground.motion.curve import segment_lengths
from lazyground.planning.space import ConfigSpace


def subdivide(space: ConfigSpace, q: list, new: list, pieces: int) -> tuple[list, list]:
    """Cut the path's segments so that none is longer than its length / ``pieces``; a piece keeps its segment's flag."""
    d = segment_lengths(space, np.array(q))
    longest = d.sum() / pieces
    out_q, out_new = [q[0]], []
    for k, length in enumerate(d):
        n = max(1, int(np.ceil(length / longest - 1e-9))) if longest > 0 else 1
        out_q.extend(space.interpolate(q[k], q[k + 1], np.arange(1, n + 1) / n))
        out_q[-1] = q[k + 1]  # the waypoint itself, not its interpolated copy
        out_new.extend([new[k]] * n)
    return out_q, out_new


def toward_segment(space: ConfigSpace, a: np.ndarray, x: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The step from x to the point of the segment a -> b nearest to x (in the space's weighted coordinates).

    For wrapping angles this is the tangent-space projection, not the chord metric's: the caller
    keeps a move only if the metric says it gains.
    """
    w2 = space.weights**2
    da, ab = space.difference(x, a), space.difference(a, b)
    den = float(np.dot(w2, ab * ab))
    s = 0.0 if den <= 0 else float(np.clip(-np.dot(w2, da * ab) / den, 0.0, 1.0))
    return da + s * ab


def relax_sweep(space: ConfigSpace, edge, q: list, new: list, born: int, halvings: int,
                min_gain: float) -> tuple[list, list, int]:
    """One pass from the start to the goal: each interior waypoint moved as far towards its neighbours'
    segment as stays free (each move sees the ones before it).

    Args:
        edge: ``edge(a, b) -> bool``, the planner's check of a straight segment.
        q, new: waypoints and per-segment flags (0: a piece of the input path; else the version that made it).
        born: the flag of the segments a move makes.
        halvings: after a blocked full step, tries at 1/2, 1/4, ... of it.
        min_gain: a move must shorten the path by at least this (saves checks on negligible moves).

    Returns:
        (waypoints, flags, moves made); start and goal are never moved.
    """
    q, new = list(q), list(new)
    moves = 0
    for k in range(1, len(q) - 1):
        a, x, b = q[k - 1], q[k], q[k + 1]
        step = toward_segment(space, a, x, b)
        before = space.distance(a, x) + space.distance(x, b)
        for t in 0.5 ** np.arange(halvings + 1):
            y = space.interpolate(x, x + step, t)
            if before - (space.distance(a, y) + space.distance(y, b)) < min_gain:
                break  # smaller steps gain less still
            if edge(a, y) and edge(y, b):
                q[k], new[k - 1], new[k] = y, born, born
                moves += 1
                break
    return q, new, moves


def relax(space: ConfigSpace, edge, q: list, new: list, born: int, pieces: int, sweeps: int, halvings: int,
          min_gain: float, in_time=lambda: True) -> list[tuple[list, list]]:
    """Subdivide (``pieces``), then up to ``sweeps`` sweeps until one moves nothing or ``in_time()`` is false.

    Returns:
        The path after each sweep that moved a waypoint, as (waypoints, flags); sweep i's moves
        are flagged ``born + i``, so a caller can go back to the path before any one sweep.
    """
    q, new = subdivide(space, q, new, pieces)
    out = []
    for i in range(sweeps):
        if not in_time():
            break
        q, new, moves = relax_sweep(space, edge, q, new, born + i, halvings, min_gain)
        if not moves:
            break
        out.append((q, new))
    return out
