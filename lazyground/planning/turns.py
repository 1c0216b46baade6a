"""Full turns of revolute joints: the same configuration at q and q + 2 pi k.

A revolute joint whose limits span more than a full turn (a UR arm's +-2 pi) reaches
the same pose at several angles. An IK answer may land on any of them; a goal that
differs from the start by most of a turn makes the arm spin where a short motion
exists. :func:`nearest_turns` moves such angles to the equivalent nearest the start;
:func:`sweeps` measures how far each joint turns along a path.
"""

from __future__ import annotations

import numpy as np

TURN = 2.0 * np.pi
HALF_TURN = np.pi - 1e-9  # closer than this, no other equivalent is as near (float error ~1e-15 kept well apart)


def nearest_turns(q: np.ndarray, start: np.ndarray, lower: np.ndarray, upper: np.ndarray, turns: np.ndarray,
                  together: tuple[np.ndarray, ...] = ()) -> np.ndarray:
    """The shift (multiples of 2 pi on ``turns`` joints) bringing ``q`` nearest ``start`` within the limits.

    Args:
        q, start, lower, upper: one configuration, the start and the limits (n,).
        turns: bool mask of the joints where q + 2 pi k is the same configuration.
        together: configurations that move with ``q`` (its pre-pose): the shift must keep them within the limits too.
    Returns:
        The shift (n,) to add to ``q`` (and to ``together``): zeros where no nearer equivalent is within the limits.
    """
    # Python floats: the same IEEE arithmetic as numpy's scalars (round: half to even, as np.round), ~10x cheaper
    q, start, lower, upper = (np.asarray(a, float).tolist() for a in (q, start, lower, upper))
    together = [np.asarray(t, float).tolist() for t in together]
    shift = np.zeros(len(q))
    for i in np.flatnonzero(turns).tolist():
        qi, si = q[i], start[i]
        if abs(qi - si) < HALF_TURN:  # q[i] itself the nearest by far: no shift (the loop below's first candidate)
            continue
        k = float(round((si - qi) / TURN))
        candidates = sorted({0.0, k - 2.0, k - 1.0, k, k + 1.0, k + 2.0}, key=lambda c: abs(qi + c * TURN - si))
        for c in candidates:  # nearest first; the limits may rule out the nearest
            values = [qi + c * TURN] + [t[i] + c * TURN for t in together]
            if c == 0.0 or all(lower[i] - 1e-9 <= v <= upper[i] + 1e-9 for v in values):
                shift[i] = c * TURN
                break
    return shift


def sweeps(path: np.ndarray, wrap: np.ndarray | None = None) -> np.ndarray:
    """Per joint, the largest distance it is from its first value anywhere along ``path`` (rows).

    ``wrap`` marks angles the space wraps: they are unwrapped first (a step across the seam is short).
    """
    path = np.array(path, float)
    if not len(path):
        return np.zeros(0)
    if wrap is not None and np.any(wrap):
        path[:, wrap] = np.unwrap(path[:, wrap], axis=0)
    return np.abs(path - path[0]).max(axis=0)


def sweep_note(path: np.ndarray, names, wrap: np.ndarray | None, turns: np.ndarray) -> str | None:
    """A note when a revolute joint (``turns``) turns more than half a turn along ``path`` (goals already take the
    nearest equivalent); ``wrap`` angles are measured across their seam."""
    if path is None or len(path) < 2:
        return None
    swept = np.where(np.asarray(turns, bool), sweeps(path, wrap), 0.0)
    i = int(np.argmax(swept))
    if swept[i] <= np.pi:
        return None
    return f"joint {names[i]} turns {swept[i]:.2f} rad along the path (more than half a turn)"
