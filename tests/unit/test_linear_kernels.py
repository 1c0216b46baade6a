"""The compiled nearest-neighbour scan and steering of unit-weight linear spaces (#31): numpy's answers."""

import numpy as np
import pytest

from lazyground.planning import PlannerSettings, solve
from lazyground.planning import linear_kernels as K
from lazyground.planning.space import ConfigSpace
from lazyground.planning.tree import Tree
from tests.unit.toy import NO_CLOCK, REACHABLE, SOLVE_BUDGET, SPACE, START, WALLS, BoxWorld, goal_source


def _space(dim: int, weights=None) -> ConfigSpace:
    return ConfigSpace(tuple(f"j{i}" for i in range(dim)), -3.0 * np.ones(dim), 3.0 * np.ones(dim), weights)


@pytest.mark.parametrize("dim", [2, 7, 8])
def test_steer_is_the_space_s_steer_bit_for_bit(dim):
    rng, space, out = np.random.default_rng(dim), _space(dim), np.empty(dim)
    for _ in range(3000):
        a, b = rng.uniform(-3, 3, dim), rng.uniform(-3, 3, dim)
        step = float(rng.choice([0.05, 0.5, 10.0]) * rng.random())
        q, reached = space.steer(a, b, step)
        assert K.steer(a, b, step, out) == reached and np.array_equal(out, q)


def test_scans_rank_as_numpy_s():
    rng = np.random.default_rng(0)
    for _ in range(300):
        dim, n, k = int(rng.choice([2, 8])), int(rng.integers(1, 300)), int(rng.integers(1, 5))
        pts = rng.uniform(-3, 3, (n + 4, dim))
        sq, x = np.einsum("ij,ij->i", pts, pts), rng.uniform(-3, 3, dim)
        g = sq[:n] + pts[:n] @ (-2.0 * x)
        assert K.nearest(pts, sq, n, x) == int(g.argmin())
        out = np.empty(k, np.int64)
        m = K.nearest_k(pts, sq, n, x, k, out)
        assert list(out[:m]) == list(np.argsort(g, kind="stable")[:k])
    assert K.nearest(pts, sq, 0, x) == -1


def test_a_tree_answers_as_without_kernels():
    # the same tree grown twice, kernels on and off: the same nearest nodes, steps and k nearest, labels too
    space, rng = _space(8), np.random.default_rng(3)
    assert space.unit_linear and not _space(8, np.full(8, 2.0)).unit_linear and not _space(16).unit_linear
    fast, slow = Tree(space, per_label=True), Tree(space, per_label=True)
    slow._kernels = slow.nn.kernels = None
    assert fast._kernels is K
    for t in (fast, slow):
        t.add_root(np.zeros(8), label=0)
        t.add_root(np.ones(8), label=1)
    for i in range(400):
        q, parent = rng.uniform(-3, 3, 8), int(rng.integers(0, i + 2))
        assert fast.add(q.copy(), parent) == slow.add(q.copy(), parent)
        if i == 200:
            fast.prune(50), slow.prune(50)
            fast.mute(1), slow.mute(1)
    for _ in range(300):
        x, label = rng.uniform(-3, 3, 8), int(rng.integers(-1, 2))
        label = None if label < 0 else label
        (i, q, r), (j, p, s) = fast.nearest_steer(x, 0.3, label), slow.nearest_steer(x, 0.3, label)
        assert (i, r) == (j, s) and np.array_equal(q, p) and i == slow.nearest(x, label)
        assert fast.nearest_k(x, 3) == slow.nearest_k(x, 3)
        q, r = fast.steer(i, x, 0.3)
        assert (q, r)[1] == slow.steer(i, x, 0.3)[1] and np.array_equal(q, slow.steer(i, x, 0.3)[0])


def test_the_kernels_take_only_the_planner_s_own_vectors():
    x = np.full(3, 2.0)
    x.setflags(write=False)  # (numba types a read-only array apart: no compiled signature takes it)
    with pytest.raises(TypeError):
        K.steer(np.zeros(3), x, 0.5, np.empty(3))
    with pytest.raises(TypeError):
        K.steer(np.zeros(3), np.zeros((3, 2))[:, 0], 0.5, np.empty(3))  # strided


class _Foreign:
    """A goal source whose samples' configurations are read-only or strided arrays."""

    def __init__(self, source, strided: bool):
        self.source, self.strided = source, strided
        self.regions, self.stats = source.regions, source.stats

    def draw(self, n, rng, stop):
        out = self.source.draw(n, rng, stop)
        for s in out:
            if self.strided:
                wide = np.zeros((len(s.q), 2))
                wide[:, 0] = s.q
                s.q = wide[:, 0]
            else:
                s.q = s.q.copy()
                s.q.setflags(write=False)
        return out

    def exhausted(self):
        return self.source.exhausted()

    @property
    def sample_time(self):
        return self.source.sample_time


@pytest.mark.parametrize("algorithm", ["rrt", "bidirectional"])
@pytest.mark.parametrize("strided", [False, True])
def test_a_goal_source_s_read_only_or_strided_samples_plan_as_plain_ones(algorithm, strided):
    # the one-tree planner steers towards a goal sample's own array: the search copies each into a planner vector
    settings = PlannerSettings(step_size=0.5, time_limit=NO_CLOCK, max_iterations=SOLVE_BUDGET, algorithm=algorithm)
    assert SPACE.unit_linear
    for seed in range(3):
        world = BoxWorld(WALLS)
        plain = solve(SPACE, world, goal_source(world, [REACHABLE]), START, settings, np.random.default_rng(seed))
        foreign = solve(SPACE, world, _Foreign(goal_source(world, [REACHABLE]), strided), START, settings,
                        np.random.default_rng(seed))
        assert plain.solved and foreign.solved
        assert foreign.iterations == plain.iterations and np.array_equal(foreign.path, plain.path)


class _NumpySpace(ConfigSpace):
    kernels = None  # (the same space on numpy's path)


def test_a_path_s_samples_and_bounds_are_numpy_s():
    # the fine re-check's discretization in one call: numpy's rows bit for bit; the bounds test as samples_free's
    rng = np.random.default_rng(11)
    for _ in range(400):
        d = int(rng.choice([2, 7, 8]))
        space = _space(d)
        ref = _NumpySpace(space.names, space.lower, space.upper)
        m, res = int(rng.integers(2, 10)), float(rng.choice([0.005, 0.02, 0.3, 10.0]))
        path = rng.uniform(-3.2, 3.2, (m, d))
        segments = sorted(rng.choice(m - 1, size=int(rng.integers(1, m)), replace=False).tolist())
        (qs, owner), (qs_ref, owner_ref) = space.discretize_path(path, segments, res), ref.discretize_path(path, segments, res)
        assert qs.tobytes() == qs_ref.tobytes() and np.array_equal(owner, owner_ref)
        inside = np.all((qs >= space.lower - 1e-9) & (qs <= space.upper + 1e-9), axis=1)
        assert K.all_inside(qs, space.lower, space.upper) == bool(inside.all())
        assert space.path_length(path) == ref.path_length(path)


@pytest.mark.parametrize("kernels", [True, False], ids=["compiled", "numpy"])
def test_a_label_s_index_built_late_answers_as_one_built_early(kernels):
    # a goal label's index is built at its first query (#31): queried from the start or only at the end, after
    # prunes and mutes, the same answers
    space, rng = _space(8), np.random.default_rng(4)
    early, late = Tree(space, per_label=True), Tree(space, per_label=True)
    if not kernels:
        for t in (early, late):
            t._kernels = t.nn.kernels = None
    for t in (early, late):
        for label in range(4):
            t.add_root(rng.uniform(-3, 3, 8) if t is early else early.nodes[label].copy(), label=label)
    for i in range(300):
        q, parent = rng.uniform(-3, 3, 8), int(rng.integers(0, i + 4))
        assert early.add(q.copy(), parent) == late.add(q.copy(), parent)
        for label in range(4):
            early.nearest(q, label)
        if i in (100, 200):
            early.prune(i // 2), late.prune(i // 2)
            early.mute(i), late.mute(i)
    assert not late._label_nn
    for _ in range(200):
        x, label = rng.uniform(-3, 3, 8), int(rng.integers(0, 5))
        (i, q, r), (j, p, s) = early.nearest_steer(x, 0.3, label), late.nearest_steer(x, 0.3, label)
        assert (i, r) == (j, s) and (q is p is None or np.array_equal(q, p)) and early.nearest(x, label) == late.nearest(x, label)
