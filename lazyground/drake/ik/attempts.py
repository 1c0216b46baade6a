"""Goal-sampling attempts of an :class:`~lazyground.drake.ik.IKGoalSource` solved many at a time (#19).

With the ``batch`` solver the source plans its attempts in round-robin order ahead
of the draw; :class:`BatchAttempts` draws their targets, screens them (reach, the
hand alone in collision), solves every restart of every attempt in one
damped-least-squares batch (:class:`~lazyground.drake.ik.solvers.BatchSolver`). When the draw comes
to them it checks their grasps (each attempt's first answer within the limits and
free) in order, as far as the samples it still wants, then solves the pre-poses of
those free grasps in a second, warm-started batch; the approach checks wait for the
attempt itself. Prepared attempts a draw did not use wait in a queue for the next
draw with the same generator.
"""

from __future__ import annotations

import math
import time
from collections import deque
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from lazyground.drake.ik.reach import reach_map
from lazyground.drake.ik.solvers import IKSolver

APPROACH_SCALES = (1.0, 0.5, 0.25)  # fractions of a region's approach distance tried in turn
KEPT_CLEAR = "kept clear"  # a draw the task's preference rules out (where an earlier choice blocked a later step)
PRE_POSE_ITERATIONS = 8  # batch solves of a pre-pose from its goal: 94-98 % converge within 5 (fetch_cans_1), none after 10


@dataclass
class Prepared:
    """One attempt of a batch: its drawn target, IK answers, grasp check and pre-poses, waiting for its approach check."""

    j: int  # region
    after: int  # round-robin counter after it (-1: made outside a draw)
    v: np.ndarray
    frame: str
    X_WT: np.ndarray  # target pose of the robot frame (4x4)
    reason: str = ""  # why the attempt failed: before any solve ("out of reach", "hand in collision") or at its grasp check
    answers: np.ndarray | None = None  # (restarts, plant positions)
    ok: np.ndarray | None = None  # (restarts,) the answer meets the pose
    k: int | None = None  # the restart whose answer is within the limits and free (the grasp)
    unchecked: bool = False  # solved, its grasp not checked yet (BatchAttempts.check)
    pre: dict = field(default_factory=dict)  # restart k -> (pre-pose answers (scales, positions), ok (scales,))
    seconds: float = 0.0  # its share of the batch's time


class BatchAttempts:
    """Prepared attempts for one IK goal source: solved in batches, queued until a draw takes them.

    It works through its source's public face: settings, regions and their target frames,
    the round-robin plan, target draws and screen, grasp checks, counters and the last
    valid answer per region.

    Args:
        source: the IKGoalSource.
        solver: solves the attempts' restarts (every frame the source's regions constrain).
        pre_solver: solves pre-poses from their goals (joints that must not pass a seam held).
    """

    def __init__(self, source, solver: IKSolver, pre_solver: IKSolver):
        self.source = source
        self.solver = solver
        self.pre_solver = pre_solver
        self.queue: deque[Prepared] = deque()
        self.rng: np.random.Generator | None = None

    def take(self, j: int, after: int, before: int, rng: np.random.Generator, look_ahead: Callable[[], int]) -> Prepared:
        """The prepared attempt on region ``j`` at round-robin counter ``before`` (``after`` once made).

        From the queue when it holds that attempt for this generator; otherwise the queue is
        dropped and the next ``look_ahead()`` attempts from ``before`` are prepared (asked only then).
        """
        if rng is not self.rng:  # answers drawn from another generator are not this draw's
            self.queue.clear()
            self.rng = rng
        if self.queue and (self.queue[0].j, self.queue[0].after) != (j, after):
            self.queue.clear()  # the round robin moved on differently (a region given up): solve afresh
        if not self.queue:
            self.queue.extend(self.prepare(self.source.plan(before, look_ahead()), rng))
        if self.queue[0].unchecked:
            self.check(self.queue)
        return self.queue.popleft()

    def prepare(self, plan: list[tuple[int, int]], rng: np.random.Generator) -> list[Prepared]:
        """Draw the planned attempts' targets and solve all their restarts in one batch per frame.

        Every attempt is charged an equal share of the drawing and screening, every
        attempt that reached the solver an equal share of the solve (each has
        ``restarts`` rows that run side by side) and its own grasp checks, every free
        grasp an equal share of the pre-pose solve. Not bounded by the clock: a batch
        of 128 attempts checks at most 3 x 128 grasps (~20 ms).
        """
        s = self.source.settings
        t0 = time.perf_counter()
        items = [Prepared(j, after, v, self.source.frames[j], X)
                 for (j, after), v, X in zip(plan, *self.source.draw_preferred([j for j, _ in plan], rng))]
        for frame in dict.fromkeys(it.frame for it in items):
            group = [it for it in items if it.frame == frame]
            for it, reason in zip(group, self.source.screen(frame, np.array([it.X_WT for it in group]))):
                it.reason = reason
        for it, avoided in zip(items, self.source.avoided([it.j for it in items], np.array([it.v for it in items]))):
            if avoided:
                it.reason = KEPT_CLEAR  # the task's preference rules this target out (IKGoalSource.prefer)
        t1 = time.perf_counter()
        for it in items:
            it.seconds = (t1 - t0) / len(items)
        for frame in dict.fromkeys(it.frame for it in items):
            group = [it for it in items if it.frame == frame and not it.reason]
            if group:
                self._solve_group(frame, group, rng)
        return items

    def _solve_group(self, frame: str, group: list[Prepared], rng: np.random.Generator) -> None:
        s = self.source.settings
        t0 = time.perf_counter()
        near = self.source.near_full()
        if near is not None and s.seed_near and s.restarts == 1:  # every solve from near: no other start to draw
            starts = np.tile(near, (len(group), 1))
        else:
            starts = self._starts(frame, group, rng)
            if s.warm_start:
                for g, it in enumerate(group):
                    if self.source.last[it.j] is not None:
                        starts[g * s.restarts] = self.source.last[it.j]
            if near is not None:
                starts[[g * s.restarts for g, it in enumerate(group) if self.source.starts_near(it.j)]] = near
        answers, ok = self.solver.solve(frame, np.repeat([it.X_WT for it in group], s.restarts, axis=0), np.array(starts))
        t1 = time.perf_counter()
        share = (t1 - t0) / len(group)
        for g, it in enumerate(group):
            rows = slice(g * s.restarts, (g + 1) * s.restarts)
            it.answers, it.ok = answers[rows], ok[rows]
            it.seconds += share
            for c in (self.source.counters, self.source.region_counters[it.j]):
                c.add(s.restarts, int(it.ok.sum()), share)
            it.unchecked = True

    def check(self, items) -> None:
        """Grasp checks of the unchecked attempts among ``items`` (in order), until the draw has half as many
        free grasps again as it still wants; then the pre-poses of those free grasps in one batch.

        Solving the pre-poses of every first answer ahead wasted them on the ~85 % that collide
        (fetch_boxes_3); checking every grasp of a look-ahead wasted the checks the draw never used.
        Neither draws from the rng: the samples are those of checking every attempt at once.
        """
        want = math.ceil(1.5 * max(self.source.wanted, 1))
        free = []
        for it in items:
            if len(free) >= want:
                break
            if not it.unchecked:
                continue
            t = time.perf_counter()
            it.k, _, it.reason = self.source.grasp(it, lambda k, it=it: it.answers[k] if it.ok[k] else None, None)
            it.unchecked = False
            it.seconds += time.perf_counter() - t
            if it.k is not None and any(self.source.regions[it.j].approach):
                free.append((it, it.k))
        for frame in dict.fromkeys(it.frame for it, _ in free):
            todo = [(it, k) for it, k in free if it.frame == frame]
            t1 = time.perf_counter()
            self.solve_pre_poses(todo)
            share = (time.perf_counter() - t1) / len(todo)
            for it, _ in todo:
                it.seconds += share

    def _starts(self, frame: str, group: list[Prepared], rng: np.random.Generator) -> np.ndarray:
        """``restarts`` starting configurations (full positions) per attempt, attempt by attempt.

        With ``reach_starts`` = K, distinct random picks among the reach-map configurations whose
        wrist points lie nearest the target's, about the K nearest (:meth:`ReachMap.near_configs`
        picks among the K / 4 nearest of every fourth): random arms, already near the pose, so a batch
        converges in fewer iterations (fetch_boxes_3's screened grasp targets, K = 256: 96 % within
        10 iterations, 99.3 % within 15; uniform random starts 85 % and 98 %); K = 0: uniform ones.
        A small K costs spread: K = 16 put a region's samples on few branches (median distance to
        the nearest other sample 0.67 rad; 256: 1.6, and 1.75 picking among every fourth; uniform: 2.3).
        """
        s, world = self.source.settings, self.source.world
        n = s.restarts
        if not s.reach_starts:
            return np.array([self.source.random_full(rng) for _ in range(len(group) * n)])
        configs = reach_map(world, frame).near_configs(np.array([it.X_WT for it in group]), n, s.reach_starts, rng)
        starts = np.tile(world.q_full, (len(group) * n, 1))
        starts[:, world.planned] = configs.reshape(-1, configs.shape[-1])
        return starts

    def solve_pre_poses(self, todo: list[tuple[Prepared, int]]) -> None:
        """Pre-poses at every APPROACH_SCALES for restart k of each attempt, from its answer, in one batch."""
        n = len(APPROACH_SCALES)
        starts, targets = [], []
        for it, k in todo:
            region = self.source.regions[it.j]
            starts += [it.answers[k]] * n
            targets += [it.X_WT @ self.source.approach_shift(region, sc) for sc in APPROACH_SCALES]
        answers, ok = self.pre_solver.solve(todo[0][0].frame, np.array(targets), np.array(starts))
        self.source.counters.add(len(ok), int(ok.sum()), 0.0)
        for i, (it, k) in enumerate(todo):
            it.pre[k] = (answers[i * n:(i + 1) * n], ok[i * n:(i + 1) * n])
