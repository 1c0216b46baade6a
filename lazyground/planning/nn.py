"""Nearest neighbours over a growing tree: a k-d tree plus a brute-force buffer.

Points go into a buffer; when the buffer outgrows a fraction of the indexed
points the k-d tree is rebuilt over all of them. A query is one k-d tree
lookup plus a vectorised scan of the buffer, so time per query grows roughly
logarithmically with tree size (amortised rebuild cost O(log n) per insert).
scipy's cKDTree is used because it is well kept and much faster than a tree
we would write in Python.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

FAR = 1e12


class NearestNeighbors:
    """Exact Euclidean nearest neighbour over points added one at a time."""

    def __init__(self, dim: int, capacity: int = 1024, rebuild_fraction: float = 0.05, min_buffer: int = 256):
        self._points = np.empty((capacity, dim))
        self._size = 0
        self._indexed = 0  # points [0, _indexed) are in the k-d tree
        self._tree: cKDTree | None = None
        self._fraction = rebuild_fraction
        self._min_buffer = min_buffer

    def __len__(self) -> int:
        return self._size

    @property
    def points(self) -> np.ndarray:
        return self._points[: self._size]

    def add(self, x: np.ndarray) -> int:
        if self._size == len(self._points):
            grown = np.empty((2 * len(self._points), self._points.shape[1]))
            grown[: self._size] = self._points[: self._size]
            self._points = grown
        self._points[self._size] = x
        self._size += 1
        if self._size - self._indexed > max(self._min_buffer, self._fraction * self._indexed):
            self._rebuild()
        return self._size - 1

    def remove(self, indices) -> None:
        """Exclude points from all later queries (their index stays reserved)."""
        self._points[np.asarray(indices, int)] = FAR
        self._rebuild()

    def nearest(self, x: np.ndarray) -> int:
        best, best_d = -1, np.inf
        if self._tree is not None:
            best_d, best = self._tree.query(x)
        buf = self._points[self._indexed : self._size]
        if len(buf):
            d = np.einsum("ij,ij->i", buf - x, buf - x)
            j = int(np.argmin(d))
            if d[j] < best_d * best_d:
                best = self._indexed + j
        return int(best)

    def _rebuild(self) -> None:
        self._indexed = self._size
        self._tree = cKDTree(self._points[: self._size]) if self._size else None
