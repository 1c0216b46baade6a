"""An edge's glue in one compiled call (lazyground.drake.edge_kernel, #31): the same ends, step count and step
orders as the checker's Python code and Drake, so the same steps and answers."""

import math

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.drake import edge_kernel as ek  # noqa: E402
from lazyground.drake import sphere_kernels as sk  # noqa: E402
from lazyground.drake.compiled import _TOY, CAP, _above  # noqa: E402
from lazyground.drake.sphere_kernels import pack, work_size  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.geometry import wrap_angle  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402


def _bisection(n):
    """The bisection order worked from its rule, as the checker built it in Python before #31's kernel: the end n,
    the start, then the middles of ever finer halvings, level by level, left to right."""
    out, seen, level = [n, 0], {0, n}, [(0, n)]
    while level:
        nxt = []
        for lo, hi in level:
            if hi - lo > 1:
                mid = (lo + hi) // 2
                if mid not in seen:
                    seen.add(mid)
                    out.append(mid)
                nxt += [(lo, mid), (mid, hi)]
        level = nxt
    return out


@pytest.mark.parametrize("n", [1, 2, 3, 7, 20, 21, 64, 100, 1000, 1025])
def test_the_compiled_step_orders_follow_their_rules(n):
    bisection = _bisection(n)
    for mode, order in ((ek.SEQUENCE, list(range(n + 1))), (ek.BISECTION, bisection),
                        (ek.INTERIOR_FIRST, bisection[2:] + bisection[1::-1])):
        assert ek.step_order(n, mode).tolist() == order


def test_the_sum_follows_eigens_packets():
    """Eigen's reduction order (Redux.h) written out for 8 and 7 squares; sequential sums differ from it."""
    rng = np.random.default_rng(2)
    differ = 0
    for _ in range(200):
        v = rng.uniform(-3, 3, 8) * 10.0 ** rng.integers(-4, 4, 8)
        s = v * v
        assert ek.squared_norm(v, 2) == ((s[0] + s[4]) + (s[2] + s[6])) + ((s[1] + s[5]) + (s[3] + s[7]))
        assert ek.squared_norm(v, 4) == ek.squared_norm(v, 2)  # for 8: two packets of 4 sum as four of 2
        assert ek.squared_norm(v[:7], 2) == ((s[0] + s[2]) + s[4]) + ((s[1] + s[3]) + s[5]) + s[6]
        assert ek.squared_norm(v[:7], 4) == (s[0] + s[2]) + (s[1] + s[3]) + s[4] + s[5] + s[6]
        seq = s[0]
        for x in s[1:]:
            seq += x
        assert ek.squared_norm(v, 1) == seq
        differ += seq != ek.squared_norm(v, 2)
    assert differ > 20


@pytest.mark.parametrize("scene", ["fetch_boxes_3", "panda_tabletop"])
def test_the_step_count_is_drakes_on_edges_an_exact_number_of_steps_long(scene):
    """A planner's steps end exactly k resolutions away, where the distance's last bit decides the count."""
    world = DrakeWorld(load_scene(scene), visual=False)
    c = world.checker
    assert c._packet in ek.PACKETS  # this Drake's sum is known
    rng = np.random.default_rng(3)
    res, same = 0.05, 0
    for _ in range(3000):
        a = world.space.sample(rng)
        d = rng.normal(size=len(a))
        b = a + d / world.space.distance(a, a + d) * res * rng.integers(1, 30)
        ek.edge_call(c._F, c._I, a, b, res, ek.BISECTION, 0, 0, 0)  # ends and count only (no step asked about)
        full = c.coordinates.full
        qa, qb = full(a), full(a + c.coordinates.space.difference(a, b))
        assert np.array_equal(c._ends[0], qa) and np.array_equal(c._ends[1], qb)
        n = max(1, math.ceil(c.drake.ComputeConfigurationDistance(qa, qb) / res))
        assert c._steps[0] == n
        same += c._steps[0] == math.ceil(np.linalg.norm(qb - qa) / res)
    assert same < 3000  # some counts hang on the last bit (numpy's sum gives another count): the test can fail


def test_the_far_end_wraps_as_the_space_does():
    """b on the shorter arc from a, bit for bit as a + space.difference(a, b) (lazyground.geometry.wrap_angle)."""
    fd, idata = pack(_TOY)
    F, I = ek.call_data(fd, idata, work_size(idata), ek.edge_data(np.zeros(1), np.ones(1), np.ones(1, bool)),
                        np.zeros(1, np.int64), 2, CAP)
    ends = ek.call_blocks(F, I)[2]
    rng = np.random.default_rng(0)
    values = np.concatenate([rng.uniform(-20, 20, (4000, 2)), [[0.0, np.pi], [np.pi, -np.pi], [-3.0, 3.2]]])
    for a, b in values:
        ek.edge_call(F, I, np.array([a]), np.array([b]), 0.1, ek.BISECTION, 0, 0, 0)
        assert ends[1, 0] == a + wrap_angle(np.array([b - a]))[0]


def test_where_the_sum_is_unknown_drake_gives_each_step_count(monkeypatch):
    """A Drake whose distance no packet width reproduces: the checker asks Drake for every count, same answers."""
    from lazyground.drake import checker as checker_module
    from lazyground.drake.certify_check import compare_edges

    monkeypatch.setattr(checker_module, "eigen_packet", lambda *a, **k: 0)
    world = DrakeWorld(load_scene("panda_tabletop"), visual=False)
    assert world.checker._packet == 0
    e = compare_edges(world, np.random.default_rng(4), 40)
    assert e.mismatches == 0 and 0 < e.free < e.edges


def test_single_checks_take_any_array_like_with_the_same_answers():
    """A checker's compiled single checks (edge_call, config_call) keep the one signature warm_up gave them (no
    compilation inside a request): a list, a read-only, strided or int array is converted, with the same answers;
    a configuration of the wrong length is an error, not a read past its end."""
    world = DrakeWorld(load_scene("fetch_boxes_3"), visual=False)
    c, rng = world.checker, np.random.default_rng(5)
    answers = set()
    for _ in range(150):
        a = world.space.sample(rng)
        b = a + (world.space.sample(rng) - a) * rng.uniform(0.02, 0.3)
        want = (c.edge_free(a, b, 0.05), c.config_free(a), c.config_unpadded_free(a), c.edge_fraction(a, b, 0.05))
        answers.add(want[:3])
        read_only = a.copy()
        read_only.setflags(write=False)
        for x in (list(a), read_only, np.repeat(a, 2)[::2]):
            assert (c.edge_free(x, b, 0.05), c.config_free(x), c.config_unpadded_free(x), c.edge_fraction(x, b, 0.05)) == want
    assert len(answers) > 2  # free and colliding configurations and edges among them
    assert c.config_free(np.zeros(len(a), int)) == c.config_free(np.zeros(len(a)))
    assert len(ek.edge_call.signatures) == len(ek.config_call.signatures) == 1
    for bad in (lambda: c.config_free(a[:-1]), lambda: c.config_unpadded_free(a[:-1]), lambda: c.edge_free(a[:-1], b, 0.05)):
        with pytest.raises(ValueError):
            bad()


def _keeps_its_memory(a: np.ndarray) -> bool:
    """Whether an array a kernel returned holds on to its memory (numba's own arrays: a memory-info base)."""
    return a.flags.owndata or a.base is not None


def test_what_the_kernels_return_keeps_its_memory():
    """The kernels' views are borrowed (sphere_kernels.c_view: no reference count, #31): one returned to Python
    would point into arrays it does not keep alive. Every array the kernels return keeps its own memory; a
    returned view would not (the control below)."""
    from numba import njit

    fd, idata = pack(_TOY)
    work, Q = np.zeros(work_size(idata)), np.array([[0.0], [0.1], [3.0]])
    outs = [sk.certify_rows(Q, fd, idata, work, np.zeros((3, CAP), np.int64)),
            sk.sweep_rows(Q, fd, idata, work, _above(_TOY), np.zeros((3, CAP), np.int64)),
            ek.step_order(5, ek.BISECTION)]
    assert all(_keeps_its_memory(a) for a in outs)
    leak = njit(lambda x: sk.c_view(x, 1, (2,)))  # a kernel returning a borrowed view (a bug)
    assert not _keeps_its_memory(leak(np.arange(4.0)))
