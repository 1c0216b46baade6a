"""A search tree (or forest) over configurations, with nearest-neighbour queries.

The start tree has one root. The bidirectional planner's goal tree is a forest
with one root per goal sample; every node carries the *label* of the goal
sample its root is, and nearest-neighbour queries can be limited to one label
(the subtree the goal-selection strategy chose).
"""

from __future__ import annotations

import numpy as np

from lazyground.planning.nn import NearestNeighbors
from lazyground.planning.space import ConfigSpace


def _as_is(q: np.ndarray) -> np.ndarray:
    return np.asarray(q, float)


_NO_IDS = np.zeros(0, np.int64)


def _put(a: np.ndarray, i: int, value) -> np.ndarray:
    """a with a[i] = value, grown (doubled) when i is past its end; returns the array to keep."""
    if i >= len(a):
        grown = np.empty((max(2 * len(a), i + 1),) + a.shape[1:], a.dtype)
        grown[: len(a)] = a
        a = grown
    a[i] = value
    return a


class Tree:
    """In a unit-weight linear space the queries and nodes go to compiled code, which takes contiguous, writable
    float vectors only (numba's signatures: lazyground.planning.linear_kernels): the planner's own arrays are,
    and :meth:`lazyground.planning.search.Search.draw` copies each goal sample's configuration into one."""

    def __init__(self, space: ConfigSpace, per_label: bool = False):
        self.space = space
        self.nodes: list[np.ndarray] = []
        self.parents: list[int] = []
        self.labels: list[int] = []
        self.goal_biased: list[bool] = []
        self.alive: list[bool] = []
        self.checked: list[bool] = []  # whether the edge from the node's parent has been collision-checked
        # a unit-weight linear space (every arm here): nearest neighbours and steering compiled (#31)
        self._kernels = getattr(space, "kernels", None)
        self.nn = NearestNeighbors(space.embed_dim, kernels=self._kernels)
        self._per_label = per_label
        self._members: dict[int, list[int]] = {}  # each label's nodes, in order
        # each label's index, built at its first query (:meth:`_label_index`): most goal roots are never
        # asked (cans_2: ~16 roots a run, a few label queries), and an index costs ~5 µs to set up (#31)
        self._label_nn: dict[int, NearestNeighbors] = {}
        self._local: list[int] = []  # index of each node in its label's index (its place among the members)
        self._muted: set[int] = set()  # nodes left out of the whole tree's queries (:meth:`mute`)
        # (coordinates that are their own embedding are not copied per query: the index copies what it keeps)
        self._embed = _as_is if getattr(space, "embeds_as_is", False) else space.embed
        # a Reeds-Shepp car: a nearest-node query is one compiled call (CarSpace.nearest_node, #33) over the nodes
        # kept in one array too, and per label the indices of its nodes
        self._car = space if getattr(space, "compiled_nearest", False) else None
        self._q = np.empty((64, space.dim)) if self._car is not None else None
        self._ids: dict[int, np.ndarray] = {}

    def __len__(self) -> int:
        return len(self.nodes)

    def add_root(self, q: np.ndarray, label: int = -1) -> int:
        return self._add(np.array(q, float), -1, label, False, True)  # (a copy of its own: contiguous, writable)

    def add(self, q: np.ndarray, parent: int, goal_biased: bool = False, checked: bool = True) -> int:
        """Add node q below ``parent``; ``checked=False`` leaves the edge between them to be checked later."""
        return self._add(q, parent, self.labels[parent], goal_biased, checked)

    def _add(self, q: np.ndarray, parent: int, label: int, goal_biased: bool, checked: bool) -> int:
        self.nodes.append(q)
        self.parents.append(parent)
        self.labels.append(label)
        self.goal_biased.append(goal_biased)
        self.alive.append(True)
        self.checked.append(checked)
        x = self._embed(q)
        i = self.nn.add(x)
        if self._car is not None:
            self._q = _put(self._q, i, q)
        if self._per_label:
            members = self._members.get(label)
            if members is None:
                members = self._members[label] = []
            self._local.append(len(members))
            members.append(i)
            nn = self._label_nn.get(label)
            if nn is not None:
                nn.add(x)
            if self._car is not None:
                self._ids[label] = _put(self._ids.get(label, _NO_IDS), self._local[-1], i)
        return i

    def _label_index(self, label: int) -> tuple[NearestNeighbors | None, list[int] | None]:
        """(the index over one label's nodes, those nodes), built on the first query as it would have grown
        node by node (pruned nodes removed); (None, None) for a label without nodes."""
        members = self._members.get(label)
        if members is None:
            return None, None
        nn = self._label_nn.get(label)
        if nn is None:
            nn = self._label_nn[label] = NearestNeighbors(self.space.embed_dim, capacity=64, kernels=self._kernels)
            for j in members:
                nn.add(self._embed(self.nodes[j]))
            dead = [self._local[j] for j in members if not self.alive[j]]
            if dead:
                nn.remove(dead)
        return nn, members

    def nearest(self, q: np.ndarray, label: int | None = None) -> int:
        """The nearest live node (of one label's subtree if given), or -1 if there is none.

        A space with ``nn_candidates`` > 1 (a car) ranks that many nearest nodes of the
        embedding by its own :meth:`closest` (the driving distance to ``q``).
        """
        if self._car is not None:
            return self._car_nearest(q, label, 0.0)[0]
        if label is None:
            nn, members = (self.nn, None) if len(self.nn) else (None, None)
        else:
            nn, members = self._label_index(label)
        return -1 if nn is None else self._general_nearest(q, nn, members)

    def _general_nearest(self, q: np.ndarray, nn: NearestNeighbors, members: list[int] | None) -> int:
        """:meth:`nearest` in ``nn`` (the whole tree's index, or a label's with its ``members``)."""
        x = self._embed(q)
        if self.space.nn_candidates > 1:
            near = nn.nearest_k(x, self.space.nn_candidates)
            near = [j for j in (near if members is None else (members[j] for j in near))
                    if self.alive[j] and (members is not None or j not in self._muted)]
            return near[self.space.closest([self.nodes[j] for j in near], q)] if near else -1
        i = nn.nearest(x)
        i = i if members is None else members[i]
        return i if i >= 0 and self.alive[i] and (members is not None or i not in self._muted) else -1

    def nearest_steer(self, q: np.ndarray, step: float, label: int | None = None) -> tuple[int, np.ndarray | None, bool]:
        """(the nearest live node (of one label's subtree if given) or -1, the configuration ``step`` from it towards
        ``q`` (:meth:`ConfigSpace.steer`), whether that reached ``q``); (-1, None, False) without a live node.

        A unit-weight linear space's scan answers it in one compiled call (the same node and numbers as
        :meth:`nearest` then ``steer``)."""
        if self._car is not None:
            return self._car_nearest(q, label, step)
        if label is None:
            nn, members = self.nn, None
        else:
            nn, members = self._label_index(label)
            if nn is None:
                return -1, None, False
        if self._kernels is not None and nn.scans:
            out = np.empty(len(q))
            code = nn.nearest_steer(q, step, out)
            if code < 0:
                return -1, None, False
            if members is None:
                i = code >> 1
                return (i, out, bool(code & 1)) if self.alive[i] and i not in self._muted else (-1, None, False)
            i = members[code >> 1]
            return (i, out, bool(code & 1)) if self.alive[i] else (-1, None, False)
        i = self.nearest(q, label)
        if i < 0:
            return -1, None, False
        q_new, reached = self.space.steer(self.nodes[i], q, step)
        return i, q_new, reached

    def _car_nearest(self, q: np.ndarray, label: int | None, step: float) -> tuple[int, np.ndarray | None, bool]:
        """:meth:`nearest_steer` (``step`` > 0) or :meth:`nearest` for a Reeds-Shepp car: one compiled call while the
        index scans (the same node and numbers as the general path below)."""
        nn, members = (self.nn, None) if label is None else self._label_index(label)
        if nn is None or not len(nn):
            return -1, None, False
        if nn.scans:
            return self._car.nearest_node(*nn.arrays(), None if label is None else self._ids[label], self._q, q, step)
        i = self._general_nearest(q, nn, members)
        if i < 0 or step <= 0.0:
            return i, None, False
        q_new, reached = self.space.steer(self.nodes[i], q, step)
        return i, q_new, reached

    def steer(self, i: int, q: np.ndarray, step: float) -> tuple[np.ndarray, bool]:
        """:meth:`ConfigSpace.steer` from node i towards ``q`` (compiled in a unit-weight linear space)."""
        if self._kernels is not None:
            out = np.empty(len(q))
            return out, self._kernels.steer(self.nodes[i], q, step, out)
        return self.space.steer(self.nodes[i], q, step)

    def nearest_k(self, q: np.ndarray, k: int) -> list[int]:
        """Up to k nearest live nodes, nearest first; only :meth:`nearest` in a space that re-ranks
        its candidates by its own distance (a car) or for k = 1."""
        if k == 1 or self.space.nn_candidates > 1:
            i = self.nearest(q)
            return [i] if i >= 0 else []
        if not len(self.nn):
            return []
        return [j for j in self.nn.nearest_k(self._embed(q), k).tolist() if self.alive[j] and j not in self._muted]

    def mute(self, i: int) -> None:
        """Leave node i out of the whole tree's nearest-neighbour queries (its label's queries still see it)."""
        self._muted.add(i)
        self.nn.remove([i])

    def chain(self, i: int) -> list[int]:
        """Node indices from ``i`` up to its root."""
        out = []
        while i >= 0:
            out.append(i)
            i = self.parents[i]
        return out

    def prune(self, i: int) -> None:
        """Drop node i and its descendants from nearest-neighbour queries."""
        dead = {i}
        for j in range(i + 1, len(self.parents)):  # children always come after parents
            if self.parents[j] in dead:
                dead.add(j)
        for j in dead:
            self.alive[j] = False
        self.nn.remove(sorted(dead))
        if self._per_label:
            by_label: dict[int, list[int]] = {}
            for j in dead:
                by_label.setdefault(self.labels[j], []).append(self._local[j])
            for label, local in by_label.items():
                nn = self._label_nn.get(label)
                if nn is not None:  # (an index built later leaves them out itself)
                    nn.remove(sorted(local))

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Nodes (n x dim), parents (int) and goal-biased flags (bool), typed even for an empty goal tree."""
        nodes = np.array(self.nodes, float).reshape(len(self.nodes), self.space.dim)
        return nodes, np.array(self.parents, int), np.array(self.goal_biased, bool)
