"""Nearest neighbours over a growing tree: two k-d trees plus a brute-force buffer.

New points go into a small buffer scanned by brute force. When the buffer is
full, it is merged into a *recent* k-d tree, rebuilt over the points since the
last major rebuild; when that grows past a fraction of the *main* k-d tree,
the main tree is rebuilt over everything. A query is two k-d tree lookups and
one vectorised scan of at most ``buffer`` points, so its cost grows roughly
logarithmically with tree size, and the amortised rebuild cost per insert
stays small (the recent tree is at most ``recent_fraction`` of the points).
scipy's cKDTree is used because it is well kept and much faster than a tree
we would write in Python.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

FAR = 1e12


class NearestNeighbors:
    """Exact Euclidean nearest neighbour over points added one at a time.

    Up to ``brute_limit`` points there is no k-d tree at all: one vectorised
    scan, written as |p|^2 - 2 p.x over stored squared norms. A cKDTree query
    costs ~30 us of CPU whatever the tree's size (scipy 1.17; two of them per
    query past the limit), a scan ~7 / 19 / 56 us over 1k / 2k / 16k points of
    an 8-D embedding, ~10 / 52 us over 2k / 16k points in 4-D (the car): the
    scan answers up to 32k points (#31; it was 1,024).
    """

    def __init__(self, dim: int, capacity: int = 1024, buffer: int = 256, recent_fraction: float = 0.25,
                 brute_limit: int = 32768, buffer_fraction: float = 1 / 64, kernels=None):
        self._points = np.empty((capacity, dim))
        self._sq = np.empty(capacity)  # squared norms of the points
        self._size = 0
        self._main: cKDTree | None = None
        self._main_end = 0  # points [0, _main_end) are in the main tree
        self._recent: cKDTree | None = None
        self._recent_end = 0  # points [_main_end, _recent_end) are in the recent tree
        self._buffer = buffer  # at least this many inserts between rebuilds of the recent tree ...
        self._buffer_fraction = buffer_fraction  # ... or this fraction of the points, whichever is more
        self._fraction = recent_fraction
        self._brute_limit = brute_limit
        self.kernels = kernels  # lazyground.planning.linear_kernels: the scans compiled (None: numpy's); a query
        # is then a contiguous, writable float vector (the kernels' signatures: lazyground.planning.tree.Tree)

    def __len__(self) -> int:
        return self._size

    @property
    def points(self) -> np.ndarray:
        return self._points[: self._size]

    def add(self, x: np.ndarray) -> int:
        if self._size == len(self._points):
            for name in ("_points", "_sq"):
                old = getattr(self, name)
                grown = np.empty((2 * len(old),) + old.shape[1:])
                grown[: self._size] = old[: self._size]
                setattr(self, name, grown)
        self._points[self._size] = x
        self._sq[self._size] = x @ x
        self._size += 1
        if self._size <= self._brute_limit:
            return self._size - 1
        # The recent tree holds up to recent_fraction of the points; rebuilding it every n/64 inserts
        # (not every 256) keeps its amortised cost flat as n grows, for a buffer scan of n/64 points.
        if self._size - self._recent_end >= max(self._buffer, self._buffer_fraction * self._size):
            if self._size - self._main_end > self._fraction * self._main_end:
                self._rebuild_main()
            else:
                self._recent_end = self._size
                self._recent = cKDTree(self._points[self._main_end : self._recent_end])
        return self._size - 1

    def remove(self, indices) -> None:
        """Exclude points from all later queries (their index stays reserved)."""
        idx = np.asarray(indices, int)
        self._points[idx] = FAR
        self._sq[idx] = np.einsum("ij,ij->i", self._points[idx], self._points[idx])
        # only points in a k-d tree need a rebuild: the buffer is scanned as it is
        if len(idx) and self._size > self._brute_limit and idx.min() < self._recent_end:
            self._rebuild_main()

    def arrays(self) -> tuple[np.ndarray, np.ndarray, int]:
        """(the points, their squared norms, how many are in use): for a compiled scan (rows past the count are
        unused)."""
        return self._points, self._sq, self._size

    @property
    def scans(self) -> bool:
        """Whether a query is one scan over every point (no k-d tree yet)."""
        return self._main is None

    def nearest_steer(self, x: np.ndarray, step: float, out: np.ndarray) -> int:
        """For points that are configurations of a unit-weight linear space, while :attr:`scans` and with
        ``kernels``: the nearest point's index i, ``out`` set to it steered towards x by at most ``step``
        (:func:`lazyground.planning.linear_kernels.nearest_steer`): 2 i + 1 if that reached x, 2 i if not;
        -1 without points."""
        return self.kernels.nearest_steer(self._points, self._sq, self._size, x, step, out)

    def nearest(self, x: np.ndarray) -> int:
        if self._main is None:  # no k-d tree yet: one scan (the answer the general path gives)
            if self.kernels is not None:
                return self.kernels.nearest(self._points, self._sq, self._size, x)
            return int(self._scan(0, x).argmin()) if self._size else -1
        d, best = self._main.query(x)  # (a recent tree exists only beside a main one)
        best_d2 = d * d
        if self._recent is not None:
            d, j = self._recent.query(x)
            if d * d < best_d2:
                best_d2, best = d * d, self._main_end + j
        lo = self._recent_end
        if lo < self._size:
            g = self._scan(lo, x)
            j = int(g.argmin())
            if g[j] + x @ x < best_d2:
                best = lo + j
        return int(best)

    def nearest_k(self, x: np.ndarray, k: int) -> np.ndarray:
        """Indices of the ``k`` nearest points (fewer if there are fewer), nearest first.

        Removed points sort last (they sit at ``FAR``); the caller filters them.
        """
        if self._main is None and self.kernels is not None:
            out = np.empty(k, np.int64)
            return out[: self.kernels.nearest_k(self._points, self._sq, self._size, x, k, out)]
        idx, d2 = [], []
        for tree, off in ((self._main, 0), (self._recent, self._main_end)):
            if tree is not None:
                d, j = tree.query(x, k=min(k, tree.n))
                keep = np.atleast_1d(j) < tree.n  # cKDTree pads missing neighbours with n
                idx.append(np.atleast_1d(j)[keep] + off)
                d2.append(np.atleast_1d(d)[keep] ** 2)
        lo = self._recent_end if self._main is not None else 0
        if lo < self._size:
            g = self._scan(lo, x) + x @ x
            j = g.argpartition(k - 1)[:k] if len(g) > k else np.arange(len(g))  # (methods: numpy's functions cost ~1 us more)
            if not idx:  # no k-d tree yet: the scan alone (what merging would give)
                return lo + j[g[j].argsort(kind="stable")]
            idx.append(lo + j)
            d2.append(g[j])
        idx, d2 = np.concatenate(idx), np.concatenate(d2)
        order = np.argsort(d2, kind="stable")[:k]
        return idx[order]

    def _scan(self, lo: int, x: np.ndarray) -> np.ndarray:
        """|p - x|^2 - |x|^2 of the points from ``lo`` on, as |p|^2 + p.(-2 x): the numbers of |p|^2 - 2 p.x
        (scaling by 2 is exact), one pass fewer over them."""
        return self._sq[lo : self._size] + self._points[lo : self._size] @ (-2.0 * x)

    def _rebuild_main(self) -> None:
        self._main_end = self._recent_end = self._size
        self._main = cKDTree(self._points[: self._size]) if self._size else None
        self._recent = None
