"""The sphere certifier's test in compiled code (#31): configurations and whole edges per call.

:class:`CompiledCertifier` runs :class:`lazyground.drake.spheres.SphereCertifier`'s
proof (same covers, solids, pairs and thresholds; its construction decides which
worlds can be bounded) per configuration in :mod:`lazyground.drake.sphere_kernels`:
~1 µs a Fetch configuration against ~25-110 µs for Drake's query. What it cannot
prove comes back as open pairs, which SceneGraph measures (the checker's fallback).
"""

from __future__ import annotations

import time

import numpy as np

from lazyground.drake import edge_kernel
from lazyground.drake import sphere_kernels as kernels
from lazyground.drake.chain import PRISMATIC
from lazyground.drake.ik import kernels as ik_kernels
from lazyground.drake.sphere_kernels import COLLIDES  # noqa: F401  (re-exported: a row's code)

CAP = 16  # open pairs kept per configuration; a configuration with more goes to Drake's whole check

_compile_s: float | None = None  # the first call's compile or cache-load time in this process
_compiled_now = False  # whether that call compiled (no usable cache on this machine) rather than loaded
_car_s: float | None = None  # the same for a car's kernels (warm_up_car)
_car_compiled = False


def warm_up() -> float:
    """Compile (or load from numba's on-disk cache) the kernels (the certifier's, the batch IK solver's and the
    planner's nearest-neighbour and steering kernels: an arm's tree would load those in its first request) once
    per process; the seconds it took (0.0 after the first call). The first call on a machine compiles (~2 minutes of
    CPU), later processes load (~1 s)."""
    global _compile_s, _compiled_now
    if _compile_s is not None:
        return 0.0
    t0 = time.perf_counter()
    fd, idata = kernels.pack(_TOY)
    work, pairs = np.zeros(kernels.work_size(idata)), np.zeros(CAP + 1, np.int64)
    kernels.certify_rows(np.zeros((1, 1)), fd, idata, work, np.zeros((1, CAP), np.int64))
    kernels.certify_one(fd, idata, work, pairs, np.zeros(1), 0.0)
    kernels.first_open(np.zeros(1), np.ones(1), 2, np.arange(3), 0, fd, idata, work, pairs)
    kernels.sweep_rows(np.zeros((2, 1)), fd, idata, work, _above(_TOY), np.zeros((2, CAP), np.int64))
    F, I = edge_kernel.call_data(fd, idata, len(work), np.array([0.0, 1.0, 0.0]), np.zeros(1, np.int64), 2, CAP)
    edge_kernel.edge_call(F, I, np.zeros(1), np.ones(1), 0.3, edge_kernel.BISECTION, 0, -1, 0)
    edge_kernel.config_call(F, I, np.zeros(1), 0.0)
    for kernel in (edge_kernel.edge_call, edge_kernel.config_call):  # a checker's single checks: this signature
        kernel.disable_compile()  # only (a call with other argument types raises TypeError: the checker converts)
    ik_compiled = ik_kernels.warm_up()  # the batch IK solver's kernels (lazyground.drake.ik.kernels)
    from lazyground.planning import linear_kernels  # (after the others: numba's compiler is up, ~0.08 s)

    planner_compiled = linear_kernels.warm_up()[1]
    from lazyground.drake import approach_kernel  # cover's approach-clearance test (lazyground.drake.approach)

    approach_kernel.retreats(np.eye(3)[None, None], np.zeros((1, 1, 3)), np.zeros((1, 3)), np.zeros((1, 1, 3)),
                             np.ones(1, np.int64), 0.03, np.zeros((1, 3)),
                             np.eye(3)[None], np.zeros((1, 3)), np.zeros(1), np.zeros((1, 3)), np.zeros(1, np.int64),
                             np.full(1, -1, np.int64), 0.01)
    planner_compiled = planner_compiled or bool(sum(approach_kernel.retreats.stats.cache_misses.values()))
    _compile_s = time.perf_counter() - t0
    _compiled_now = ik_compiled or planner_compiled or any(sum(k.stats.cache_misses.values()) for k in (
        kernels.certify_rows, kernels.certify_one, kernels.first_open, kernels.sweep_rows,
        edge_kernel.step_order, edge_kernel.edge_call, edge_kernel.config_call))
    return _compile_s


def warm_up_car() -> float:
    """Load (or compile, once per machine) a Reeds-Shepp car's planner kernels (:mod:`lazyground.planning.car_kernels`)
    once per process, for :func:`compile_report`; the seconds it took (0.0 after the first call). A car's world has no
    certifier, so :func:`warm_up` never runs there: its set-up calls this (``Worlds.warm_kernels``)."""
    global _car_s, _car_compiled
    if _car_s is not None:
        return 0.0
    from lazyground.planning import car_kernels

    t0 = time.perf_counter()
    _car_compiled = car_kernels.warm_up()
    _car_s = time.perf_counter() - t0
    return _car_s


def compile_report() -> tuple[float, bool] | None:
    """(seconds this process spent getting the kernels, whether it compiled any rather than loading numba's
    cache); None before the first use. Part of the set-up (the world build), never of a request's time."""
    parts = [(s, c) for s, c in ((_compile_s, _compiled_now), (_car_s, _car_compiled)) if s is not None]
    return (sum(s for s, _ in parts), any(c for _, c in parts)) if parts else None


class CompiledCertifier:
    """A SphereCertifier's data in two flat arrays, and its test per configuration and per edge."""

    def __init__(self, cert):
        assert PRISMATIC == kernels.PRISMATIC_KIND
        warm_up()
        blocks = cert.kernel_blocks()
        self.fd, self.idata = kernels.pack(blocks)
        self._above = _above(blocks)
        self._open = np.zeros(CAP + 1, np.int64)
        self.work = np.zeros(kernels.work_size(self.idata))

    def certify_one(self, q_full: np.ndarray, shift: float = 0.0) -> tuple[int, np.ndarray | None]:
        """(the code of one configuration (:meth:`certify`), its open pairs when it has some). ``shift``: the
        padding, to ask whether any pair penetrates instead (0 and the open pairs: against every pair's threshold
        less it; COLLIDES is still a padded collision), where every checked pair has that one padding."""
        code = kernels.certify_one(self.fd, self.idata, self.work, self._open, q_full, shift)
        return code, (self._open[:code].copy() if code > 0 else None)

    def certify(self, q_full: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(per row of plant positions: its open pairs' count, 0 certified free, -1 too many to list,
        COLLIDES proven colliding; (rows, CAP) the open pairs, indices into SphereCertifier.pair_geometries)."""
        q = np.ascontiguousarray(np.atleast_2d(q_full), float)
        pairs = np.empty((len(q), CAP), np.int64)
        return kernels.certify_rows(q, self.fd, self.idata, self.work, pairs), pairs

    def sweep(self, q_full: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`certify` of rows in sequence, each close to the one before (a densely checked path): a row
        within reach of an earlier one certified with room to spare is certified from it
        (lazyground.drake.sphere_kernels.sweep_rows); the others get the whole test. The same codes where those are 0."""
        q = np.ascontiguousarray(np.atleast_2d(q_full), float)
        pairs = np.empty((len(q), CAP), np.int64)
        return kernels.sweep_rows(q, self.fd, self.idata, self.work, self._above, pairs), pairs

    def first_open(self, qa: np.ndarray, qb: np.ndarray, steps: int, order: np.ndarray, begin: int = 0):
        """The first position p >= begin of ``order`` whose configuration qa + order[p] / steps (qb - qa) is not
        certified, and its code (:meth:`certify`) and open pairs (None: too many to list or colliding);
        (-1, 0, None) when all are."""
        p = kernels.first_open(qa, qb, steps, order, begin, self.fd, self.idata, self.work, self._open)
        if p < 0:
            return -1, 0, None
        count = int(self._open[-1])
        return p, count, (self._open[:count].copy() if count > 0 else None)


def _above(blocks: dict) -> np.ndarray:
    """(geometries, joints): 1 where the joint is above the geometry's body in the tree (moving it moves the geometry)."""
    parent, slot, node = (np.asarray(blocks[k], np.int64).reshape(-1) for k in ("parent", "slot", "node"))
    above = np.zeros((len(node), len(parent)), np.int64)
    for g, b in enumerate(node):
        s = slot[b]
        while s > 0:  # slot s is joint s - 1's frame; slot 0 the world
            above[g, s - 1] = 1
            s = parent[s - 1]
    return above


# the smallest certifier the kernels accept: one revolute joint, a sphere, a box (for warm_up's compilation)
_TOY = dict(
    counts=dict(m=1, n=1, G=1, S=1, O=1, P=0, I=1),
    ic=np.zeros(3), ir=[0.05], below=[2e-4], reach2=[[0.01]], istart=[0, 1], gexact=[1], oexact=[1],
    K=np.eye(4)[:3], F=np.eye(4)[:3], gR=np.eye(3), go=np.zeros(3), ghalf=np.zeros(3), ground=[0.1], grad=[0.1],
    sc=np.zeros(3), sr=[0.1], oR=np.eye(3), oo=[1.0, 0.0, 0.0], ohalf=[0.1, 0.1, 0.1], oround=[0.0],
    ac=[1.0, 0.0, 0.0], ah=[0.1, 0.1, 0.1], env=[[0.01]], self_thr=np.zeros(0), parent=[0], kinds=[0], index=[0],
    slot=[1], node=[0], start=[0, 1], gcyl=[0], ocyl=[0], mover=np.zeros(0), other=np.zeros(0))
