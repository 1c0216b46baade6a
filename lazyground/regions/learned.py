"""Draws within goal regions that learn where earlier draws worked (issue 34).

A can in an open box: of a top grasp's yaws only a few let the fingers pass the walls, and a
uniform draw found one in ~1 of 100 tries, so seeds that drew none gave the region up. Here
each free axis of a region (a yaw, a tilt, a height, a depth) is cut into bins, and every
attempt scores the bins its draw fell in: 1 for a valid goal (IK reached it, collision-free),
``REACHED_SCORE`` when IK reached it but the arm collided, 0 otherwise (out of reach, the hand
alone in collision, IK failed). A bin's weight is its mean score under a Beta(1, 1) prior (an
untried bin weighs 1/2), and later draws follow, per axis, the density that puts the share
``learning`` of the axis in proportion to the weights and the rest uniformly over the whole
range: no part of a region is ever ruled out.

A draw is the inverse CDF of that density applied to the caller's uniform numbers, so it takes
exactly the Generator's draws a uniform one takes, and until a region has outcomes (or with
``learning`` 0) it is the uniform draw itself.
"""

from __future__ import annotations

import math

import numpy as np

REACHED_SCORE = 0.25  # IK reached the pose, the arm collided: the pose is reachable, another arm may be free
BIN_ANGLE = math.pi / 6  # rad: bin width on an angle axis (roll, pitch, yaw)
BIN_LENGTH = 0.01  # m: bin width on a length axis
MAX_BINS = 12
ANGLES = (3, 4, 5)  # a pose region's angle axes


class RegionLearner:
    """Per region and free axis, the binned scores of past draws and the warp of new ones.

    Args:
        bounds: ``(lower, span, wrapped)``, (N, dim) each, a row per region, as
            :func:`~lazyground.regions.base.unit_maps` gives them.
        learning: the share of each axis's density that follows the scores, in [0, 1].
        angles: the axes measured in radians (binned by BIN_ANGLE, the others by BIN_LENGTH).
    """

    def __init__(self, bounds, learning: float, angles=ANGLES):
        if not 0.0 <= learning <= 1.0:
            raise ValueError(f"learning must be in [0, 1], got {learning}")
        self.learning = float(learning)
        self._lower, self._span, self._wrapped = (np.asarray(b, float) for b in bounds)
        span = self._span
        # per region: {axis: number of bins}, the axes wide enough for two bins (all regions in one pass, #33)
        width = np.where(np.isin(np.arange(span.shape[1]), angles), BIN_ANGLE, BIN_LENGTH)
        n = np.minimum(MAX_BINS, np.ceil(span / width - 1e-9)).astype(int)
        self._bins: list[dict[int, int]] = [{} for _ in range(len(span))]
        for j, i in zip(*(a.tolist() for a in np.nonzero(n > 1))):
            self._bins[j][i] = int(n[j, i])
        self._tallies: dict[int, tuple[dict, dict]] = {}  # region -> ({axis: scores}, {axis: counts}), made when first scored

    def tallies(self, j: int) -> tuple[dict[int, np.ndarray], dict[int, np.ndarray]]:
        """Region ``j``'s ({axis: summed score per bin}, {axis: draws per bin}) (zeros until it is scored)."""
        if j not in self._tallies:
            self._tallies[j] = ({i: np.zeros(n) for i, n in self._bins[j].items()}, {i: np.zeros(n) for i, n in self._bins[j].items()})
        return self._tallies[j]

    def weights(self, j: int, axis: int) -> np.ndarray:
        """The density of region ``j``'s ``axis`` over its bins (sums to 1)."""
        score, count = self.tallies(j)
        w = (score[axis] + 1.0) / (count[axis] + 2.0)
        n = len(w)
        return (1.0 - self.learning) / n + self.learning * w / w.sum()

    def warp(self, regions, u: np.ndarray) -> np.ndarray:
        """Unit draws ``u`` (N, dim) for regions ``regions`` (N,) moved to each region's learned density."""
        u = np.array(u, float)
        if self.learning == 0.0:
            return u
        regions = np.asarray(regions, int)
        for j in np.unique(regions):
            if j not in self._tallies:  # no outcomes yet: the uniform draw
                continue
            rows = regions == j
            count = self._tallies[j][1]
            for axis in self._bins[j]:
                if not count[axis].any():
                    continue
                w = self.weights(j, axis)
                cdf = np.concatenate([[0.0], np.cumsum(w)])
                cdf[-1] = 1.0
                edges = np.linspace(0.0, 1.0, len(w) + 1)
                u[rows, axis] = np.interp(u[rows, axis], cdf, edges)
        return np.minimum(u, np.nextafter(1.0, 0.0))

    def record(self, j: int, v: np.ndarray, score: float) -> None:
        """Score ``score`` (0..1) for the draw ``v`` of region ``j`` on every free axis's bin (angles unwrapped onto
        the range); on Python floats, one axis at a time (the same IEEE operations as numpy's, ~10x cheaper here)."""
        lo, span, wrapped = self._lower[j], self._span[j], self._wrapped[j]
        score_j, count_j = self.tallies(j)
        for axis, n in self._bins[j].items():  # a binned axis has span > 0
            d = float(v[axis]) - float(lo[axis])
            if wrapped[axis]:
                d %= 2 * math.pi  # np.mod's result for a positive divisor
            u = min(max(d / float(span[axis]), 0.0), 1.0 - 1e-12)
            b = min(int(u * n), n - 1)
            score_j[axis][b] += score
            count_j[axis][b] += 1.0


def outcome_score(reason: str, reached_reasons=("in collision",)) -> float | None:
    """An attempt's score from its failure reason ("" for a valid goal); None for no evidence (ran out of time)."""
    if reason == "":
        return 1.0
    if reason == "time":
        return None
    return REACHED_SCORE if reason in reached_reasons else 0.0
