"""Motion validators: whether the motion along an edge of a space is free (OMPL's ``MotionValidator``).

A space builds its validator from a checker (:meth:`ConfigSpace.motion_validator`), so the
planners ask one object and never which kind of space they search: a space whose edges are
straight lines in its coordinates hands edges to the checker's own edge check (Drake's
interpolates linearly); a space with curved edges (a car's) checks the samples its own
``discretize`` takes along them, against the space's bounds too (a curve between two nodes
inside the bounds can leave them).
"""

from __future__ import annotations

import numpy as np


def samples_free(space, checker, qs: np.ndarray) -> np.ndarray:
    """Which configurations ``qs`` (samples along edges) are valid: inside the space's bounds and free.

    Nodes are sampled inside the bounds, and a straight edge between two stays inside them; a car's curve
    need not (issue 34: paths around walls at a lot's edge drove up to 6 m outside it), so every sample is
    held to the bounds where it is checked for collision."""
    qs = np.asarray(qs, float)
    kernels = getattr(space, "kernels", None)  # (a unit-weight linear space: one compiled pass, #31)
    if kernels is not None and qs.ndim == 2 and qs.flags.c_contiguous and kernels.all_inside(qs, space.lower, space.upper):
        return np.asarray(checker.configs_free(qs), bool)
    inside = np.all((qs >= space.lower - 1e-9) & (qs <= space.upper + 1e-9), axis=1)
    if inside.all():
        return np.asarray(checker.configs_free(qs), bool)
    free = np.zeros(len(qs), bool)
    if inside.any():
        free[inside] = np.asarray(checker.configs_free(qs[inside]), bool)
    return free


class MotionValidator:
    """Edges checked by the checker itself: straight lines in the space's coordinates."""

    def __init__(self, space, checker):
        self.space, self.checker = space, checker

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the edge a -> b is free, checked no coarser than ``resolution``."""
        return self.checker.edge_free(a, b, resolution)

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The largest checked fraction t such that a -> interpolate(a, b, t) is free (the free prefix)."""
        return self.checker.edge_fraction(a, b, resolution)


class SampledMotionValidator(MotionValidator):
    """Edges checked at the space's own samples along them (curved edges: the checker cannot interpolate them)."""

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        return bool(np.all(samples_free(self.space, self.checker, self.space.discretize(a, b, resolution, skip_first=True))))

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        space = self.space
        qs = space.discretize(a, b, resolution, skip_first=True)
        blocked = np.flatnonzero(~samples_free(space, self.checker, qs))
        if not len(blocked):
            return 1.0
        if blocked[0] == 0:
            return 0.0
        # samples need not be evenly spaced (a car samples each segment on its own): the fraction of the
        # distance to the last free sample, which interpolate maps back to it (a shortest path's prefix
        # is the shortest path to its end)
        return space.distance(a, qs[blocked[0] - 1]) / space.distance(a, b)
