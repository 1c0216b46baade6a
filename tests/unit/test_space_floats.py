"""The linear space's float and lean numpy paths give numpy's numbers bit for bit (#31: plans stay the same per seed)."""

import numpy as np
import pytest

from lazyground.planning.space import ConfigSpace
from lazyground.planning.tree import Tree

NAMES = tuple(f"q{i}" for i in range(8))
LOWER, UPPER = np.array([0.0, -1.6, -1.2, -np.pi, -2.25, -np.pi, -2.16, -np.pi]), np.array([0.39, 1.6, 1.5, np.pi, 2.25, np.pi, 2.16, np.pi])


def reference_distance(space, a, b):
    d = b - a
    return float(np.sqrt(np.dot(space.weights**2, d * d)))


def reference_steer(space, a, b, step):
    d = b - a
    n = float(np.sqrt(np.dot(space.weights**2, d * d)))
    return (b.copy(), True) if n <= step else (a + (step / n) * d, False)


@pytest.mark.parametrize("weighted", [False, True], ids=["unit", "weighted"])
def test_linear_space_matches_numpy_bit_for_bit(weighted):
    rng = np.random.default_rng(7)
    weights = rng.random(8) + 0.5 if weighted else None
    space = ConfigSpace(NAMES, LOWER, UPPER, weights=weights)
    assert space._w2_list is not None and space.embeds_as_is is not weighted
    for i in range(3000):
        a, b = space.sample(rng), space.sample(rng)
        if i % 3 == 0:
            b = a + rng.normal(size=8) * 0.05
        step = float(rng.choice([0.05, 0.5, 1.0, 4.0]))
        assert space.distance(a, b) == reference_distance(space, a, b)
        q, reached = space.steer(a, b, step)
        q_ref, reached_ref = reference_steer(space, a, b, step)
        assert reached == reached_ref and q.tobytes() == q_ref.tobytes()
        t = float(rng.random())
        assert space.interpolate(a, b, t).tobytes() == (a + np.multiply.outer(np.asarray(t), b - a)).tobytes()


def test_sample_draws_lower_plus_r_times_span():
    space = ConfigSpace(NAMES, LOWER, UPPER)
    r1, r2 = np.random.default_rng(3), np.random.default_rng(3)
    for _ in range(500):
        assert space.sample(r1).tobytes() == (space.lower + r2.random(8) * (space.upper - space.lower)).tobytes()


def test_tree_without_embedding_copies_finds_the_same_nearest():
    rng = np.random.default_rng(1)
    unit = ConfigSpace(NAMES, LOWER, UPPER)
    scaled = ConfigSpace(NAMES, LOWER, UPPER, weights=np.full(8, 2.0))  # embeds (x2: the same order of distances)
    t1, t2 = Tree(unit), Tree(scaled)
    for q in [unit.sample(rng) for _ in range(300)]:
        t1.add_root(q)
        t2.add_root(q)
    for q in [unit.sample(rng) for _ in range(300)]:
        assert t1.nearest(q) == t2.nearest(q)
        assert t1.nearest_k(q, 3) == t2.nearest_k(q, 3)


def test_a_path_discretized_at_once_is_segment_by_segment():
    # discretize_path's numpy calls over every segment give discretize's numbers, a shared vertex once (#31)
    rng = np.random.default_rng(5)
    for _ in range(400):
        d = int(rng.choice([2, 8]))
        weights = None if rng.random() < 0.5 else rng.uniform(0.5, 2.0, d)
        space = ConfigSpace(tuple(f"j{i}" for i in range(d)), -3.0 * np.ones(d), 3.0 * np.ones(d), weights)
        m, res = int(rng.integers(2, 10)), float(rng.choice([0.02, 0.3, 10.0]))
        path = rng.uniform(-3, 3, (m, d))
        segments = sorted(rng.choice(m - 1, size=int(rng.integers(1, m)), replace=False).tolist())
        qs, owner = space.discretize_path(path, segments, res)
        want = [space.discretize(path[k], path[k + 1], res, skip_first=i > 0 and segments[i - 1] == k - 1)
                for i, k in enumerate(segments)]
        assert np.array_equal(qs, np.vstack(want))
        assert np.array_equal(owner, np.concatenate([np.full(len(w), k) for k, w in zip(segments, want)]))
