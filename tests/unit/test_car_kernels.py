"""The car's compiled curve queries give the numbers their Python gives, bit for bit (#33: a seed plans the same run).

numba lowers math.sin, cos, atan2, asin, acos and sqrt to libm's, as CPython does, but its math.hypot is libm's
and CPython's is its own correctly rounded one: curves.hypot is CPython's algorithm. The kernels are run again as
plain Python (NUMBA_DISABLE_JIT, in a subprocess) on the same inputs and must agree exactly; a car tree's compiled
nearest-node query must pick the node and step of the general path it replaces.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

from lazyground.planning import car_kernels, curves
from lazyground.planning.kinematics import make_space
from lazyground.planning.space import ConfigSpace
from lazyground.planning.tree import Tree

ROOT = Path(__file__).resolve().parents[2]
R, OFF = 3.2, -1.4  # a turning radius and rear-axle offset like the lots' car


def _queries(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    q = np.column_stack([rng.uniform(-12, 12, n), rng.uniform(-12, 12, n), rng.uniform(-math.pi, math.pi, n)])
    q[: n // 8, :2] *= 1e-3  # near the start, where arcs and cusps compete
    q[n // 8: n // 4, 1] = 0.0  # straight ahead or behind
    q[n // 4: n // 4 + n // 16, 2] = 0.0
    return q


def _outputs() -> dict:
    """Every kernel's output on fixed inputs, as hex floats (run compiled here and interpreted in a subprocess)."""
    out: dict = {"rs": [], "steer": [], "discretize": [], "poses": []}
    w = np.empty((curves.MAX_SEGMENTS, 2))
    pairs = _queries(400, 1)
    for x, y, phi in _queries(1500, 0).tolist():
        n = curves.reeds_shepp(x, y, phi, w)
        out["rs"].append([v.hex() for v in w[:n].ravel().tolist()])
    for a, b in zip(pairs[:200], pairs[200:]):
        n = car_kernels.solve(a, b, R, OFF, w)
        q, head = np.empty(3), np.empty((curves.MAX_SEGMENTS, 2))
        m = car_kernels.steer(a, w[:n], 0.7, R, OFF, q, head)
        out["steer"].append([v.hex() for v in q.tolist() + head[:m].ravel().tolist()])
        qs = car_kernels.discretize(a, b, w[:n], 0.05, False, math.hypot(1.0, OFF / R), 0.1, R, OFF)
        out["discretize"].append([v.hex() for v in qs.ravel().tolist()])
        p = np.empty((3, 3))
        car_kernels.poses(a, w[:n], np.array([0.3, 1.7, 40.0]), R, OFF, p)
        out["poses"].append([v.hex() for v in p.ravel().tolist()])
    return out


def test_hypot_is_cpythons_bit_for_bit():
    rng = np.random.default_rng(3)
    a, b = rng.uniform(-20, 20, 20000), rng.uniform(-20, 20, 20000)
    a[:2000] *= 1e-9
    b[2000:2100] = 0.0
    for x, y in zip(a.tolist() + [0.0, 3.0, -0.0, 5e-324], b.tolist() + [0.0, 4.0, 2.0, 5e-324]):
        assert curves.hypot(x, y) == math.hypot(x, y), (x, y)


def test_the_kernels_compute_what_their_python_computes():
    code = ("import json, sys; sys.path.insert(0, '.'); sys.path.insert(0, 'tests/unit');"
            "import test_car_kernels as t; print(json.dumps(t._outputs()))")
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, check=True)
    interpreted = json.loads(done.stdout)
    compiled = _outputs()
    for kind in compiled:
        bad = [i for i, (c, p) in enumerate(zip(compiled[kind], interpreted[kind])) if c != p]
        assert not bad and len(compiled[kind]) == len(interpreted[kind]), (kind, bad[:5])


def test_a_car_trees_compiled_nearest_is_the_general_paths():
    """Random forests with pruned and muted nodes: the compiled query picks the general path's node (the
    embedding's 5 nearest live nodes re-ranked by curve length) and steers to the same pose."""
    base = ConfigSpace(("x", "y", "th"), np.array([0.0, 0.0, -np.pi]), np.array([60.0, 40.0, np.pi]), None,
                       np.array([False, False, True]))
    space = make_space(base, "reeds-shepp", R, offset=OFF)
    rng = np.random.default_rng(7)
    for trial in range(4):
        tree = Tree(space, per_label=True)
        for i in range(300):
            q = space.sample(rng)
            if i < 20 or rng.random() < 0.2:
                tree.add_root(q, label=i % 20)
            else:
                tree.add(q, int(rng.integers(len(tree))))
        for i in rng.choice(len(tree), 30, replace=False).tolist():
            if tree.alive[i]:
                tree.mute(i) if rng.random() < 0.5 else tree.prune(i)
        for _ in range(200):
            q = space.sample(rng)
            label = None if rng.random() < 0.5 else int(rng.integers(21))  # (label 20 has no tree)
            step = float(rng.choice([0.0, 0.5, 2.0, 50.0]))
            got = tree._car_nearest(q, label, step)
            nn, members = (tree.nn, None) if label is None else tree._label_index(label)
            want = -1 if nn is None else tree._general_nearest(q, nn, members)
            assert got[0] == want, (trial, label)
            if want >= 0 and step > 0.0:
                q_new, reached = space.steer(tree.nodes[want], q, step)
                assert got[2] == reached and np.array_equal(got[1], q_new)
