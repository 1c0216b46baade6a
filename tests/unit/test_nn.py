"""Nearest neighbours: exact against brute force across rebuild boundaries and removals."""

import numpy as np
import pytest

from lazyground.planning.nn import NearestNeighbors

PATHS = pytest.mark.parametrize("brute_limit", [0, 1024], ids=["k-d trees", "scan first"])


@PATHS
def test_exact_nearest_through_growth(brute_limit):
    rng = np.random.default_rng(0)
    nn = NearestNeighbors(4, capacity=8, buffer=16, brute_limit=brute_limit)
    pts = rng.random((3000, 4))
    for i, p in enumerate(pts):
        if i:
            q = rng.random(4)
            j = nn.nearest(q)
            d = np.linalg.norm(pts[:i] - q, axis=1)
            assert np.isclose(d[j], d.min())
        assert nn.add(p) == i
    assert len(nn) == 3000


@PATHS
def test_removed_points_are_never_returned(brute_limit):
    rng = np.random.default_rng(1)
    nn = NearestNeighbors(2, buffer=8, brute_limit=brute_limit)
    pts = rng.random((200, 2))
    for p in pts:
        nn.add(p)
    gone = list(range(0, 200, 3))
    nn.remove(gone)
    for _ in range(200):
        q = rng.random(2)
        j = nn.nearest(q)
        assert j not in gone
        alive = np.setdiff1d(np.arange(200), gone)
        assert np.isclose(np.linalg.norm(pts[j] - q), np.linalg.norm(pts[alive] - q, axis=1).min())


@PATHS
def test_k_nearest_match_brute_force_through_growth_and_removal(brute_limit):
    rng = np.random.default_rng(2)
    nn = NearestNeighbors(3, capacity=8, buffer=16, brute_limit=brute_limit)
    pts = rng.random((1500, 3))
    gone = set()
    for i, p in enumerate(pts):
        nn.add(p)
        if i % 97 == 96:  # removals between inserts, as a pruned branch
            nn.remove([i - 5, i - 3])
            gone |= {i - 5, i - 3}
        if i % 7 == 0:
            q, k = rng.random(3), int(rng.integers(1, 12))
            got = [j for j in nn.nearest_k(q, k) if j not in gone]
            alive = np.setdiff1d(np.arange(i + 1), sorted(gone))
            d = np.linalg.norm(pts[alive] - q, axis=1)
            assert len(got) == min(k, len(alive))  # removed points sort last (they sit far away)
            assert np.allclose(np.linalg.norm(pts[got] - q, axis=1), np.sort(d)[: len(got)]), (i, got)


def test_tree_nearest_k_gives_the_k_nearest_live_nodes_nearest_first():
    from lazyground.planning.space import ConfigSpace
    from lazyground.planning.tree import Tree

    rng = np.random.default_rng(3)
    space = ConfigSpace(("x", "y"), np.zeros(2), np.ones(2))
    tree = Tree(space)
    tree.add_root(rng.random(2))
    for i in range(1, 300):
        tree.add(rng.random(2), int(rng.integers(0, i)))
    tree.prune(7)  # a branch: node 7 and its descendants
    nodes, alive = np.array(tree.nodes), np.flatnonzero(tree.alive)
    assert len(alive) < 300
    for _ in range(50):
        q = rng.random(2)
        d = np.linalg.norm(nodes[alive] - q, axis=1)
        got = tree.nearest_k(q, 3)
        assert list(got) == list(alive[np.argsort(d)[:3]])
        assert tree.nearest_k(q, 1) == [tree.nearest(q)] == got[:1]


def test_empty_and_empty_removal():
    nn = NearestNeighbors(2)
    assert nn.nearest(np.zeros(2)) == -1
    nn.add(np.array([1.0, 1.0]))
    nn.remove([])
    assert nn.nearest(np.zeros(2)) == 0 and list(nn.nearest_k(np.zeros(2), 3)) == [0]

