"""The search tree on hand-built trees: pruning a branch, nearest queries and typed arrays."""

import numpy as np

from lazyground.planning.kinematics import make_space
from lazyground.planning.space import ConfigSpace
from lazyground.planning.tree import Tree

PLANE = ConfigSpace(("x", "y"), np.zeros(2), np.full(2, 10.0))


def hand_tree():
    """0 (root) -> 1 -> 2 -> 4, 0 -> 3 -> 5, on a line at x = index."""
    t = Tree(PLANE)
    t.add_root(np.array([0.0, 0.0]))
    for q, parent in (([1.0, 0.0], 0), ([2.0, 0.0], 1), ([3.0, 0.0], 0), ([4.0, 0.0], 2), ([5.0, 0.0], 3)):
        t.add(np.array(q), parent)
    return t


def test_pruning_drops_the_node_and_its_descendants_only():
    t = hand_tree()
    t.prune(1)
    assert t.alive == [True, False, False, True, False, True]
    assert t.nearest(np.array([2.1, 0.0])) == 3  # 2 and 4 are gone, 3 is nearest of what is left
    assert t.nearest_k(np.array([2.1, 0.0]), 3) == [3, 0, 5]
    t = hand_tree()
    t.prune(3)
    assert t.alive == [True, True, True, False, True, False]


def test_nearest_k_of_one_is_the_nearest_node_root_included():
    t = Tree(PLANE)
    assert t.nearest(np.zeros(2)) == -1 and t.nearest_k(np.zeros(2), 1) == [] and t.nearest_k(np.zeros(2), 3) == []
    t.add_root(np.array([1.0, 1.0]))
    assert t.nearest_k(np.array([9.0, 9.0]), 1) == [0]
    t = hand_tree()
    assert t.nearest_k(np.array([2.2, 0.0]), 1) == [2]
    assert t.nearest_k(np.array([2.2, 0.0]), 2) == [2, 3]


def test_a_car_tree_answers_nearest_k_with_its_one_driving_nearest():
    """A car ranks candidates by driving distance: nearest_k gives that one node, whatever k."""
    base = ConfigSpace(("x", "y", "th"), np.array([0.0, 0.0, -np.pi]), np.array([40.0, 40.0, np.pi]), None,
                       np.array([False, False, True]))
    car = make_space(base, "reeds-shepp", 3.0)
    t = Tree(car)
    t.add_root(np.array([10.0, 10.0, 0.0]))
    t.add(np.array([10.0, 12.0, np.pi / 2]), 0)  # 2 m away but turned: a long drive
    t.add(np.array([6.0, 10.0, 0.0]), 0)  # 4 m behind, heading the same way: 4 m of straight reverse
    q = np.array([10.0, 10.0, 0.0]) + [0.5, 0.0, 0.0]
    assert t.nearest(q) == 0 and t.nearest_k(q, 3) == [0]


def test_arrays_are_typed_even_when_empty():
    nodes, parents, biased = Tree(PLANE).arrays()
    assert nodes.shape == (0, 2) and nodes.dtype == float
    assert parents.dtype.kind == "i" and biased.dtype == bool
    nodes, parents, biased = hand_tree().arrays()
    assert parents.tolist() == [-1, 0, 1, 0, 2, 3] and biased.dtype == bool and nodes[4].tolist() == [4.0, 0.0]


def test_a_goal_forest_answers_per_label_and_prunes_per_label():
    """The bidirectional planner's goal forest: one root per goal sample, nodes carry their root's label."""
    t = Tree(PLANE, per_label=True)
    t.add_root(np.array([0.0, 0.0]), label=0)
    t.add_root(np.array([10.0, 0.0]), label=1)
    t.add(np.array([1.0, 0.0]), 0)
    t.add(np.array([9.0, 0.0]), 1, goal_biased=True)
    t.add(np.array([2.0, 0.0]), 2, checked=False)
    assert t.labels == [0, 1, 0, 1, 0]
    assert t.goal_biased == [False, False, False, True, False] and t.checked == [True, True, True, True, False]
    q = np.array([8.0, 0.0])
    assert t.nearest(q) == 3 and t.nearest(q, label=0) == 4 and t.nearest(q, label=7) == -1
    t.prune(2)  # 2 and 4
    assert t.nearest(q, label=0) == 0 and t.nearest(np.array([1.5, 0.0]), label=1) == 3
    assert t.nearest(np.array([1.5, 0.0])) == 0
    t.prune(0)
    assert t.nearest(q, label=0) == -1 and t.nearest(q) == 3
    nodes, parents, biased = t.arrays()
    assert biased.shape == (5,) and biased.tolist() == [False, False, False, True, False]


def test_nothing_is_nearest_once_every_node_is_pruned():
    t = hand_tree()
    t.prune(0)
    assert t.nearest(np.array([1.0, 0.0])) == -1 and t.nearest_k(np.array([1.0, 0.0]), 1) == []
    base = ConfigSpace(("x", "y", "th"), np.array([0.0, 0.0, -np.pi]), np.array([40.0, 40.0, np.pi]), None,
                       np.array([False, False, True]))
    car = Tree(make_space(base, "reeds-shepp", 3.0))
    car.add_root(np.array([10.0, 10.0, 0.0]))
    car.add(np.array([12.0, 10.0, 0.0]), 0)
    car.prune(0)
    assert car.nearest(np.array([11.0, 10.0, 0.0])) == -1
