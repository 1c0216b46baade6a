"""Drake's ``SceneGraphCollisionChecker`` behind the planner's ValidityChecker protocol.

One :class:`DrakeChecker` checks edges at one resolution, fixed once: at
construction, or (when built without one) by its first edge check. Drake's
edge step size is never rewritten afterwards; a caller that needs another
resolution asks :class:`lazyground.drake.world.DrakeWorld`, which keeps one
checker per resolution.
"""

from __future__ import annotations

import math
import time

import numpy as np
from pydrake.planning import LinearDistanceAndInterpolationProvider, SceneGraphCollisionChecker

from lazyground.drake.compiled import CAP, COLLIDES, CompiledCertifier
from lazyground.drake.edge_kernel import (ALL_FREE, BISECTION, INTERIOR_FIRST, SEQUENCE, call_blocks, call_data,
                                          config_call, edge_call, edge_data, eigen_packet, step_order)
from lazyground.drake.coordinates import Coordinates
from lazyground.drake.parallel import parallel_batch
from lazyground.drake.spheres import sphere_certifier

_clock = time.perf_counter

# A batch this long is certified as configurations in sequence (CompiledCertifier.sweep): the search's re-check of
# a path it returns (~1,000-3,000 rows a few mm apart on Fetch: 1.5-3x cheaper a row); shorter batches (goal
# samples' approaches, the segments a rejected path left unchecked: 2-200 rows) cost more that way (#31).
SWEEP_ROWS = 512

# Drake needs a positive step at construction; a checker built without a resolution
# replaces this once, before its first edge check, and never again.
_UNSET_STEP = 0.05
class DrakeChecker:
    """Config and edge checks over planned coordinates, in C++.

    Args:
        diagram: the scene's RobotDiagram (the checker takes ownership).
        robot: the robot's ModelInstanceIndex.
        coordinates: the planned coordinates (for ``full`` and the metric weights).
        padding: collision padding in metres, against the environment and the robot itself.
        edge_resolution: spacing of edge checks in the planner's weighted metric;
            None fixes it at the first edge check.
        certify: prove batches free with :mod:`lazyground.drake.spheres` before asking
            Drake (the answers are Drake's either way).
    """

    def __init__(self, diagram, robot, coordinates: Coordinates, padding: float, edge_resolution: float | None = None,
                 certify: bool = True):
        self.coordinates = coordinates
        # one configuration's plant positions (_full_one): Coordinates.full's broadcast and list index cost ~3 µs a
        # single check on Fetch, a copy and an index array ~0.4 µs (#31)
        self._q_start = np.array(coordinates.q_full, float)
        self._planned = np.asarray(coordinates.planned, np.int64)
        self.padding = padding
        self._resolution = edge_resolution
        # Drake's edge checks step in the same weighted metric as ours (fixed coordinates weigh 0).
        self.drake = SceneGraphCollisionChecker(
            model=diagram,
            robot_model_instances=[robot],
            distance_and_interpolation_provider=LinearDistanceAndInterpolationProvider(diagram.plant(), coordinates.plant_weights()),
            edge_step_size=_UNSET_STEP if edge_resolution is None else edge_resolution,
            env_collision_padding=padding,
            self_collision_padding=padding,
        )
        self.check_time = 0.0
        self.checks = 0
        self._context = self.drake.model_context()  # the main thread's context (the one single checks use)
        # SceneGraph's query object for that context: the same object on every call (its queries read the
        # context's current poses), fetched once here: ~1 us a check (#19)
        self._query = self._context.GetQueryObject()
        self.penetration_first = _candidates_all_checked(self.drake)
        self.unpadded_shift = max(self.drake.GetLargestPadding(), 0.0)  # every pair's padding where that holds
        # proves configurations free before Drake is asked (None: this world cannot be bounded; lazyground.drake.spheres),
        # in compiled code (lazyground.drake.compiled)
        self.certifier = sphere_certifier(self.drake) if certify else None
        self.compiled = CompiledCertifier(self.certifier) if self.certifier is not None else None
        # bound once: an edge check's glue is a fifth of its cost on Fetch (#31)
        self._difference = coordinates.space.difference
        self._distance = self.drake.ComputeConfigurationDistance
        if self.compiled is not None:  # an edge's glue and steps in one compiled call (edge_kernel.edge_call)
            # how this Drake sums its distance (0: unknown; then Drake gives each step count): a fixed seed
            self._packet = eigen_packet(self._distance, coordinates.plant_weights(), np.random.default_rng(0))
            # the certifier's and the edges' arrays in two (numba unboxes each argument on every call, #31)
            F, I = call_data(self.compiled.fd, self.compiled.idata, len(self.compiled.work),
                             edge_data(coordinates.q_full, coordinates.plant_weights(), coordinates.space.wrap),
                             self._planned, self._packet, CAP)
            self._F, self._I = F, I
            # what the kernels write: open pairs then the code, an edge's step count and ends, a single check's q
            self._open, self._steps, self._ends, self._one = call_blocks(F, I)
        self.certified = 0  # configurations the certifier proved free
        self._pairs = {}  # the certifier's pairs as SceneGraph's (id, id, padding), as they come up (_pair)

    @property
    def edge_resolution(self) -> float | None:
        """The fixed edge-check spacing (None until the first edge check of a checker built without one)."""
        return self._resolution

    def accepts(self, resolution: float) -> bool:
        """Whether edges at ``resolution`` can be checked here (the fixed one, or none fixed yet; any with a
        certifier, which steps edges itself)."""
        return self._resolution is None or self._resolution == resolution or self.compiled is not None

    def config_free(self, q: np.ndarray) -> bool:
        t0 = _clock()
        if self.compiled is None:
            free = self._free(self._full_one(q))
        else:
            free = self._decide(self._code(q, 0.0))
        self.check_time += _clock() - t0
        self.checks += 1
        return free

    def config_unpadded_free(self, q: np.ndarray) -> bool:
        """Whether q is free of penetration: SceneGraph's boolean query alone (~25 µs), the padding not checked.

        :meth:`config_free` implies it, so False is Drake's answer too. For tentative checks that a
        padded check follows before anything is returned (the two-tree planner's lazy start tree).
        Where the boolean query cannot stand in for the checker's (see _candidates_all_checked),
        this is :meth:`config_free`.
        """
        if not self.penetration_first:
            return self.config_free(q)
        t0 = _clock()
        if self.compiled is None:
            free = not self.penetrates(self._full_one(q))
        else:  # the certifier's test for penetration (thresholds less the padding; COLLIDES: a padded collision,
            # False here as before), then the open pairs' penetration (every other pair is proven apart)
            code = self._code(q, self.unpadded_shift)
            free = code == 0 or code != COLLIDES and (
                self._open_free(self._one.copy(), self._open[:code].copy(), unpadded=True) if code > 0
                else not self.penetrates(self._one.copy()))
        self.check_time += _clock() - t0
        self.checks += 1
        return free

    def _code(self, q: np.ndarray, shift: float) -> int:
        """The certifier's code for planned coordinates q (:func:`lazyground.drake.edge_kernel.config_call`; its plant
        positions in ``_one``, its open pairs in ``_open``): one compiled call, q as it comes (a contiguous float array
        from the planner: the call's only signature, :func:`lazyground.drake.compiled.warm_up`), else as one."""
        try:
            return config_call(self._F, self._I, q, shift)
        except TypeError:
            return config_call(self._F, self._I, np.array(q, float), float(shift))

    def _full_one(self, q: np.ndarray) -> np.ndarray:
        """``coordinates.full(q)`` of one configuration (the same values, a new array)."""
        out = self._q_start.copy()
        out[self._planned] = q
        return out

    def _free(self, q_full: np.ndarray) -> bool:
        """Drake's config check, answered by a cheaper boolean query first when that query can decide.

        Drake's checker asks for every geometry pair's signed distance up to the padding,
        which costs ~125 µs on a colliding Fetch configuration (penetration depths) and
        ~65 µs on a free one. SceneGraph's boolean ``HasCollisions`` answers in ~25 µs; when
        it finds a penetration, Drake's check would too (every pair SceneGraph considers is
        one the checker checks, with one padding, not negative: see _candidates_all_checked).
        Otherwise the distance query runs on the same, already posed context: the checker's
        own test, so the answer is Drake's either way (benchmarks/RESULTS.md, #19).
        """
        if not self.penetration_first:
            return bool(self.drake.CheckConfigCollisionFree(q_full))
        if self.penetrates(q_full):
            return False
        return not self._query.ComputeSignedDistancePairwiseClosestPoints(self.drake.GetLargestPadding())

    def penetrates(self, q_full: np.ndarray) -> bool:
        """SceneGraph's boolean collision query at q_full (left posed in the main thread's context)."""
        self.drake.UpdatePositions(q_full)
        return self._query.HasCollisions()

    def configs_free(self, qs: np.ndarray) -> np.ndarray:
        qs = np.atleast_2d(qs)
        if len(qs) == 1:
            return np.array([self.config_free(qs[0])])
        t0 = time.perf_counter()
        free = self._batch(self.coordinates.full(qs))
        self.check_time += time.perf_counter() - t0
        self.checks += len(qs)
        return free

    def configs_free_along(self, qs: np.ndarray) -> np.ndarray:
        """:meth:`configs_free` of configurations in sequence, each close to the one before (a path checked
        densely): the same answers, most of them proven from an earlier configuration's clearance
        (:meth:`CompiledCertifier.sweep`); :meth:`configs_free` where there is no certifier."""
        qs = np.atleast_2d(qs)
        if self.compiled is None or len(qs) == 1:
            return self.configs_free(qs)
        t0 = time.perf_counter()
        free = self._batch(self.coordinates.full(qs), along=True)
        self.check_time += time.perf_counter() - t0
        self.checks += len(qs)
        return free

    def _batch(self, configs: np.ndarray, along: bool = False) -> np.ndarray:
        """The batch's answers: the certifier proves what it can (``along``: rows in sequence, :meth:`configs_free_along`,
        or a batch of SWEEP_ROWS or more)
        and SceneGraph measures the pairs it leaves open (:meth:`_open_free`); a world without certifier goes to
        Drake's batch check, on several threads when that is many (lazyground.drake.parallel)."""
        if self.compiled is None:
            return np.asarray(self.drake.CheckConfigsCollisionFree(list(configs), parallelize=parallel_batch(len(configs))), bool)
        along = along or len(configs) >= SWEEP_ROWS
        count, pairs = (self.compiled.sweep if along else self.compiled.certify)(configs)
        free = count == 0
        self.certified += int(free.sum())
        for i in np.flatnonzero(count > 0):
            free[i] = self._open_free(configs[i], pairs[i, :count[i]])
        for i in np.flatnonzero(count == -1):
            free[i] = self._free(configs[i])
        return free

    def _decide(self, code: int) -> bool:
        """Drake's answer at the configuration in ``_one`` from the certifier's ``code`` for it (its open pairs in
        ``_open``)."""
        if code == 0:
            self.certified += 1
            return True
        if code == COLLIDES:
            return False
        return self._open_free(self._one.copy(), self._open[:code].copy() if code > 0 else None)

    def _open_free(self, q_full: np.ndarray, pairs: np.ndarray | None, unpadded: bool = False) -> bool:
        """Drake's answer at ``q_full``, which the certifier left open, from SceneGraph's signed distance of its
        open pairs only (None: too many to list, Drake's own check).

        Drake's checker calls a configuration colliding when some pair it checks has signed distance <= the
        pair's padding, and the certifier proved every pair but the open ones farther than their padding; so
        the open pairs decide. SceneGraph's distance of one pair is the computation its all-pairs query makes
        for that pair (the same narrow-phase callback and request; the same numbers bit for bit on ~97k pairs
        of near-contact Fetch and Panda configurations, #16). A pair SceneGraph cannot measure alone (it
        throws) sends the configuration to the checker's own check. ``unpadded``: whether they penetrate
        (distance <= 0), for :meth:`config_unpadded_free`.
        """
        if pairs is None:
            return self._free(q_full)
        self.drake.UpdatePositions(q_full)
        try:
            for k in pairs:
                a, b, padding = self._pair(k)
                if self._query.ComputeSignedDistancePairClosestPoints(a, b).distance <= (0.0 if unpadded else padding):
                    return False
        except RuntimeError:
            return bool(self.drake.CheckConfigCollisionFree(q_full))
        return True

    def _pair(self, k: int):
        """(GeometryId, GeometryId, padding) of the certifier's pair k (remembered)."""
        if k not in self._pairs:
            ids = self.certifier.geometry_ids
            a, b = (ids[g] for g in self.certifier.pair_geometries[k])
            inspector = self.drake.model().scene_graph().model_inspector()
            body_a, body_b = (self.drake.plant().GetBodyFromFrameId(inspector.GetFrameId(g)) for g in (a, b))
            self._pairs[k] = (a, b, self.drake.GetPaddingBetween(body_a, body_b))
        return self._pairs[k]

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the motion a → b is free, checked in C++ every ``resolution`` with early exit.

        Drake interpolates linearly, so b is first unwrapped onto the shorter arc
        from a (an angle of 3.5 rad is the same pose as -2.78 rad). Drake's
        weighted metric counts an angle step w·|dθ|, never less than our chord,
        so its steps are at least as fine as ``resolution`` in our metric.

        Raises:
            ValueError: ``resolution`` is not this checker's fixed resolution.
        """
        if self.compiled is not None:
            return self._certified_edge(a, b, resolution, BISECTION)
        return bool(self._edge(self._edge_free, a, b, resolution))

    def _edge_free(self, qa: np.ndarray, qb: np.ndarray) -> bool:
        """Drake's ``CheckEdgeCollisionFree``, after SceneGraph's boolean query at b.

        Most of a planner's steps end in collision (on fetch_boxes_3, 70-87 % of the
        extensions), and Drake checks b first but with its full distance query; the
        boolean query rejects those edges ~4x cheaper. An edge it lets through gets
        Drake's own check (b, then a and the steps towards b), so the answer is Drake's.
        Replayed on a plan's edges this was the cheapest of three variants; checking
        the steps ourselves in one batch was slower (Python overhead on the cheap car
        checks, no early exit on the arm; benchmarks/RESULTS.md, #19).
        """
        if self.penetration_first and self.penetrates(qb):
            return False
        return bool(self.drake.CheckEdgeCollisionFree(qa, qb))

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The largest t in [0, 1] with a → a + t (b - a) free at ``resolution`` (1: all free; 0: blocked at once).

        Drake's ``MeasureEdgeCollisionFree``: the last free check before the first
        collision, as OMPL's ``checkMotion(s1, s2, lastValid)``.

        Raises:
            ValueError: ``resolution`` is not this checker's fixed resolution.
        """
        if self.compiled is not None:
            return self._certified_edge(a, b, resolution, SEQUENCE)
        measure = self._edge(self.drake.MeasureEdgeCollisionFree, a, b, resolution)
        return max(0.0, measure.alpha_or(0.0))

    def edge_part_free(self, a: np.ndarray, b: np.ndarray, resolution: float, first: int = 0,
                       stop: int | None = None) -> bool:
        """Whether the steps at positions ``first`` .. ``stop`` - 1 of a → b, in interior-first bisection order
        (:func:`lazyground.drake.edge_kernel.step_order`, INTERIOR_FIRST), are free at ``resolution``: the whole edge by default, in one compiled call with
        early exit (a shortcut's candidate edges, whose ends lie on a checked path; a search probing a few steps
        first). The steps and answers are :meth:`edge_free`'s (Drake's); only the order and the part differ.

        Raises:
            ValueError: this checker has no compiled certifier (a car's: Drake checks its edges).
        """
        if self.compiled is None:
            raise ValueError("edge_part_free needs the compiled certifier")
        return self._certified_edge(a, b, resolution, INTERIOR_FIRST, first, -1 if stop is None else stop)

    def _certified_edge(self, a: np.ndarray, b: np.ndarray, resolution: float, mode: int, first: int = 0,
                        stop: int = -1):
        """Drake's ``CheckEdgeCollisionFree`` (``mode`` SEQUENCE: ``MeasureEdgeCollisionFree``'s free fraction) at
        ``resolution``, with the certifier: the same steps (q_k = qa + k / n (qb - qa), k = 0..n, n =
        max(1, ceil(Drake's distance / resolution)); the certifier's margin covers the last bit by which Drake's
        interpolation may differ, and a step it leaves open is Drake's interpolation), certified in one compiled
        call (:func:`lazyground.drake.edge_kernel.edge_call`: the ends, the step count, the order and the steps)
        in bisection order (sequentially for the fraction) up to the first one it cannot prove, which
        SceneGraph decides (:meth:`_open_free`) unless it proves a collision there; then on from there. So the answer is Drake's: a step is
        called colliding by Drake or by a proof of it, and every other step is proven free."""
        if self._resolution is None:
            self._resolution = resolution
        t0 = _clock()
        steps = 0 if self._packet else self._drake_steps(a, b, resolution)
        try:  # a and b as they come (contiguous float arrays from a planner: the call's one signature, warm_up)
            p = edge_call(self._F, self._I, a, b, resolution, mode, first, stop, steps)
        except TypeError:  # anything else as such arrays
            p = edge_call(self._F, self._I, np.array(a, float), np.array(b, float), float(resolution), mode, int(first),
                          int(stop), steps)
        if p == ALL_FREE:
            out = 1.0 if mode == SEQUENCE else True
        elif p < ALL_FREE and mode != SEQUENCE:  # a step proven colliding: most of a planner's edges
            out = False
        else:
            out = self._open_steps(p if p >= 0 else -2 - p, mode, stop, mode == SEQUENCE)
        self.check_time += _clock() - t0
        self.checks += 1
        return out

    def _drake_steps(self, a: np.ndarray, b: np.ndarray, resolution: float) -> int:
        """The step count of a -> b from Drake's own distance (where edge_kernel cannot sum as this Drake does)."""
        full, a = self.coordinates.full, np.asarray(a, float)
        return max(1, math.ceil(self._distance(full(a), full(a + self._difference(a, b))) / resolution))

    def _open_steps(self, p: int, mode: int, stop: int, fraction: bool):
        """The rest of :meth:`_certified_edge` from the first step the certifier left open (position p of the
        order; the ends in ``_ends``, the count in ``_steps``): SceneGraph decides it, then on from there."""
        (qa, qb), n = self._ends, int(self._steps[0])
        order = step_order(n, mode)  # (the kernel's order: rebuilt only when a step is left open)
        order = order if stop < 0 else order[:stop]
        code = int(self._open[-1])
        pairs = self._open[:code].copy() if code > 0 else None
        while True:
            k = int(order[p])
            # Drake's own interpolation: ours differs in the last bit, which decides a step on the boundary
            q = qa if k == 0 else qb if k == n else self.drake.InterpolateBetweenConfigurations(qa, qb, k / n)
            if code == COLLIDES or not self._open_free(q, pairs):
                return max(0.0, (k - 1) / n) if fraction else False
            p, code, pairs = self.compiled.first_open(qa, qb, n, order, p + 1)
            if p < 0:
                return 1.0 if fraction else True

    def _edge(self, check, a, b, resolution: float):
        if self._resolution is None:
            self.drake.set_edge_step_size(resolution)  # the one time: fixes this checker's resolution
            self._resolution = resolution
        elif resolution != self._resolution:
            raise ValueError(f"this collision checker checks edges every {self._resolution:g}, not {resolution:g}")
        t0 = time.perf_counter()
        a = np.asarray(a, float)
        out = check(self.coordinates.full(a), self.coordinates.full(a + self.coordinates.space.difference(a, b)))
        self.check_time += time.perf_counter() - t0
        self.checks += 1
        return out

    def colliding_pairs(self, q: np.ndarray) -> list[tuple[str, str]]:
        """Names of the geometry pairs within the padding at ``q``, sorted."""
        self.drake.UpdatePositions(self.coordinates.full(q))
        plant = self.drake.plant()
        sg = self.drake.model().scene_graph()
        sg_ctx = sg.GetMyContextFromRoot(self.drake.model_context().model_context())
        query = sg.get_query_output_port().Eval(sg_ctx)
        inspector = query.inspector()
        pairs = []
        for p in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=self.padding + 1e-9):
            if p.distance > self.padding:
                continue
            pairs.append((_geometry_name(plant, inspector, p.id_A), _geometry_name(plant, inspector, p.id_B)))
        return sorted(set(pairs))


def _candidates_all_checked(checker) -> bool:
    """Whether every geometry pair SceneGraph may report is a pair the checker checks, with one padding.

    Then a penetration SceneGraph finds is a collision for the checker, and a pair it
    reports within the padding is one too (the checker's own rule), so its queries
    can stand in for the checker's. Decided once, at construction: lazyground never
    changes a checker's filters or padding afterwards.
    """
    plant = checker.plant()
    inspector = checker.model().scene_graph().model_inspector()
    paddings = checker.GetPaddingMatrix()
    bodies = set()
    for ga, gb in inspector.GetCollisionCandidates():
        a, b = (plant.GetBodyFromFrameId(inspector.GetFrameId(g)) for g in (ga, gb))
        if a is None or b is None or checker.IsCollisionFilteredBetween(a, b):
            return False
        bodies.add((int(a.index()), int(b.index())))
    pads = {paddings[i, j] for i, j in bodies}
    return pads <= {checker.GetLargestPadding()} and checker.GetLargestPadding() >= 0.0


def _geometry_name(plant, inspector, gid) -> str:
    body = plant.GetBodyFromFrameId(inspector.GetFrameId(gid))
    if body is None or body.index() == plant.world_body().index():
        return inspector.GetName(gid).split("::")[-1]
    return body.name()
