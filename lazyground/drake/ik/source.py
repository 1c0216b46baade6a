"""The IK goal source: round-robin attempts over pose regions, each aimed at a free approach.

One attempt on a region: draw a 6-vector v in the region, turn it into a
target pose of the end-effector frame, screen it (:mod:`~lazyground.drake.ik.screen`),
solve IK for that pose over the planned coordinates from ``restarts`` starts
(kinematics only: position box and orientation cone, joint limits), then confirm
the first answer that meets the pose with the collision checker, and its straight
approach from a pre-pose.

Two ways to solve (``IKSettings.solver``; :mod:`~lazyground.drake.ik.solvers`):

* ``batch`` (the default): every attempt of a look-ahead in round-robin order
  is solved at once by damped least squares on the chain
  (:mod:`~lazyground.drake.ik.attempts`), ~10 µs per solve (compiled) against ~1.5 ms for a
  SNOPT program built per solve; collision checks then run attempt by attempt,
  only as far as the draw needs (#19).
* ``snopt`` / ``ipopt``: a Drake ``InverseKinematics`` program, one solve at a time;
  also what ``batch`` falls back to for a frame the chain cannot express (a planar
  or floating base).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Callable

import numpy as np

from lazyground.drake.ik import settings as ik_settings
from lazyground.drake.ik.attempts import APPROACH_SCALES, PRE_POSE_ITERATIONS, BatchAttempts, Prepared
from lazyground.drake.ik.screen import TargetScreen
from lazyground.drake.ik.settings import IKCounters, IKSettings
from lazyground.drake.ik.batch import pose_errors
from lazyground.drake.ik.solvers import BatchSolver, ProgramSolver, pose_error, problem_for_frame
from lazyground.geometry import Pose, rpy_to_matrices
from lazyground.goals import RoundRobinGoalSource
from lazyground.planning.problem import GoalSample
from lazyground.planning.stop import StopCondition
from lazyground.planning.turns import nearest_turns
from lazyground.regions import PoseRegion
from lazyground.regions.base import from_unit
from lazyground.regions.learned import RegionLearner, outcome_score
from lazyground.regions.table import pose_table
from lazyground.settings import GoalSamplingSettings
from lazyground.typed_yaml import SceneError

APPROACH_RESOLUTION = 0.01  # rad (or m): spacing of the collision checks along an approach segment
NEAR_CANDIDATES = 32  # near_targets: targets drawn per attempt; the one nearest the frame's pose at the start is solved
NEAR_METRES_PER_RAD = 0.5  # ... "nearest": rotation angle plus distance / this (a wrist turn costs its angle, a reach more)
LOOK_AHEAD_MIN = 16  # fewest attempts the batch solver solves at once (below, one iteration's overhead dominates)


def _region_table(world, regions: tuple, attached) -> tuple:
    """(frames, index, the shared :class:`~lazyground.regions.table.PoseTable`) of ``regions`` in ``world``.

    Raises:
        ValueError: a region is not a pose region, or a placement region without a carried object.
        SceneError: the robot has no frame a region constrains.
    """
    for r in regions:
        if not isinstance(r, PoseRegion):
            raise ValueError(f"region {r.id} is a {r.kind} region, not a pose region; use its registered goal source")
    table = pose_table(regions, attached)  # raises for a placement without a carried object
    for frame, j in {f: j for j, f in reversed(list(enumerate(table.frames)))}.items():  # each frame, its first region
        if not world.plant.HasFrameNamed(frame):  # a scene/request mismatch, not a bug
            raise SceneError(f"{world.scene.source}: robot: no frame {frame!r} to reach goal region {regions[j].id} with (set robot.end_effector)")
    # X_WT = X_WR · X_RS(v) · X_SE · X_ET, where robot_target's X_ET takes the region's target to the robot frame
    # (identity, or the carried object's grasp); the approach, given in the target's axes, is X_ET^-1 · T(approach) · X_ET
    return table.frames, {r.id: j for j, r in enumerate(regions)}, table


class IKGoalSource(RoundRobinGoalSource):
    """Valid goal configurations for pose regions (workspace, placement), by IK.

    Args:
        regions: :class:`~lazyground.regions.PoseRegion` goal regions (placement
            regions need a world carrying an attached object).
        world: the :class:`~lazyground.drake.world.DrakeWorld` to solve in.
        settings: IK tolerances and per-attempt limits (default: ``settings.DEFAULT_IK_SETTINGS``).
        **kwargs: :class:`RoundRobinGoalSource` options.

    Raises:
        ValueError: a region is not a pose region, or a placement region without a carried object.
        SceneError: the robot has no frame a region constrains.

    A sample records ``extra = {"X_WG": Pose, "v": 6-vector, "frame": name}``.
    With the ``batch`` solver, attempts are solved up to ``batch_attempts`` at a time
    ahead of the draw; the answers not used yet wait for the next draw with the
    same generator (another generator drops them, so a draw's samples come from
    its own generator's stream).
    """

    reached_reasons = ("in collision",)  # IK reached the grasp, the arm collided: another grasp of the region may not
    hopeless_reasons = ("out of reach",)  # the wrist point beyond the sampled reach (screened before any solve)
    screened_reasons = ("out of reach", "hand in collision")  # TargetScreen's reasons (RoundRobinGoalSource.deferred)

    def __init__(self, regions: tuple[PoseRegion, ...], world, settings: IKSettings | None = None, **kwargs):
        super().__init__(regions, **kwargs)
        sampling = kwargs.get("sampling")
        if settings is None:  # the run's restarts and solver over the IK defaults
            settings = ik_settings.DEFAULT_IK_SETTINGS if sampling is None else replace(
                ik_settings.DEFAULT_IK_SETTINGS, restarts=sampling.ik_restarts, solver=str(sampling.ik_solver))
        attached = getattr(world, "attached", None)
        # per region: the robot frame its targets are for, its row in the table of their numbers (_region_table)
        self.frames, self._index, self._table = _region_table(world, self.regions, attached)
        self.world = world
        self.settings = settings
        self.counters = IKCounters()
        self.region_counters = [IKCounters() for _ in self.regions]
        self._kinematics = world.kinematics
        self.planned = np.asarray(world.planned, int)
        self.last: list[np.ndarray | None] = [None] * len(self.regions)  # per region: its last valid answer
        self.target_screen = TargetScreen(world, self.frames, settings)
        self.near = world.start  # goals prefer the full-turn equivalent nearest this (the step's start)
        # which of several drawn targets to try (a task's placement preference, e.g. leave room for later
        # objects; lazyground/tasks/packing.py): an object with ``draws``, ``pick(j, V)`` -> (N, 6) and
        # ``avoided(j, V)`` -> (N,) bool; None: one draw per attempt (:meth:`draw_preferred`; batch solver only)
        self.prefer = None
        self._turns = getattr(getattr(world, "coordinates", None), "turns", None)
        problems = {f: problem_for_frame(world, f) for f in dict.fromkeys(self.frames)} if settings.solver == "batch" else {}
        # batches when the chain expresses every frame (else SNOPT on the plant, e.g. for a planar base)
        self.batch = None
        if problems and None not in problems.values():
            # A pre-pose solved from its goal must not pass a joint's seam: the approach from it is
            # a straight segment in the planner's space, which does not wrap there (a pre-pose across
            # the seam of a [-pi, pi] roll made a full-turn "approach": ~600 checks, then blocked).
            pre = {f: problem_for_frame(world, f, full_turns=False) for f in problems}
            self.batch = BatchAttempts(self, BatchSolver(problems, settings), BatchSolver(pre, settings, PRE_POSE_ITERATIONS))
        self.wanted = 1  # samples the current draw still wants (sizes the batch solver's look-ahead)
        # draws follow, within each region, the sub-ranges whose earlier draws worked (issue 34)
        self.learner = RegionLearner((self._table.lower, self._table.span, self._table.wrapped),
                                     (sampling or GoalSamplingSettings()).goal_learning)
        self.program = ProgramSolver(world, settings)

    # --- hooks -------------------------------------------------------------------------------
    def target_pose_for(self, region: PoseRegion, v: np.ndarray, approach: bool = False, scale: float = 1.0) -> tuple[str, Pose]:
        """The robot frame to constrain and its target pose X_WT for a draw ``v`` of ``region``.

        The region says which frame (:meth:`PoseRegion.robot_target`): a workspace
        region its end-effector frame, a placement region the body carrying the
        world's attached object. With ``approach``, the pre-pose: the target moved
        by ``scale`` times ``region.approach`` in its own axes.
        """
        X = self._target_matrix(region, v)
        if approach:
            X = X @ self.approach_shift(region, scale)
        return self.frames[self._index[region.id]], Pose.from_matrix(X)

    def _target_matrix(self, region: PoseRegion, v: np.ndarray) -> np.ndarray:
        """X_WT (4x4) of the robot frame for a draw ``v``: X_WR · X_RS(v) · X_ST, with X_ST from the region and robot."""
        return self.target_poses(np.array([self._index[region.id]]), np.asarray(v, float)[None])[0]

    def target_poses(self, regions: np.ndarray, V: np.ndarray) -> np.ndarray:
        """:meth:`_target_matrix` of draws ``V`` (N, 6) of regions ``regions`` (N,) (indices) at once, (N, 4, 4)."""
        X_WR, X_ST = self._table.X_WR[regions], self._table.X_ST[regions]
        X_RS = np.zeros((len(V), 4, 4))
        X_RS[:, :3, :3] = rpy_to_matrices(V[:, 3:6])
        X_RS[:, :3, 3] = V[:, :3]
        X_RS[:, 3, 3] = 1.0
        return X_WR @ X_RS @ X_ST

    def draw_targets(self, regions: list[int], rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """Draws v (N, 6) and target poses X_WT (N, 4, 4) for attempts on ``regions`` (indices, in order): the
        draws one ``self.regions[j].sample(rng)`` each would make, in one ``rng.random((N, 6))``."""
        j = np.asarray(regions, int)
        if self.settings.near_targets and self.near is not None and len(j):
            return self._near_targets(j, rng)
        lo, span, wrapped = (a[j] for a in (self._table.lower, self._table.span, self._table.wrapped))
        V = from_unit(lo, span, wrapped, self.learner.warp(j, rng.random(lo.shape)))
        return V, self.target_poses(j, V)

    def _near_targets(self, j: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`draw_targets` when solving from ``near``: per attempt NEAR_CANDIDATES draws, the one whose target
        asks the least joint motion from ``near`` kept, at first order (|J+ (rotation; translation)| with the
        frame's Jacobian at ``near``; without a batch chain, the rotation angle plus distance / NEAR_METRES_PER_RAD).
        A free yaw of a top grasp drawn so turns the wrist least. Straight length start -> pre-pose -> grasp of the
        cup's top grasp, median of 80 samples (seeds 0-9): ur5e_tabletop 4.71 rad drawn as the first search
        draws, 1.96 solved from the start, 0.90 with the nearest of 16 targets by angle and distance, 0.88 / 0.87 /
        0.85 by joint motion with 16 / 32 / 64 targets; panda_tabletop 3.62, 1.87, 1.71, 1.59 / 1.57 / 1.56
        (64 targets cost ~40 ms per 90 attempts, 32 ~20 ms)."""
        rows = np.repeat(j, NEAR_CANDIDATES)
        lo, span, wrapped = (a[rows] for a in (self._table.lower, self._table.span, self._table.wrapped))
        V = from_unit(lo, span, wrapped, rng.random(lo.shape))
        X = self.target_poses(rows, V)
        near_full = self.near_full()
        names = list(dict.fromkeys(self.frames[i] for i in j))
        code = np.array([names.index(self.frames[i]) for i in j]).repeat(NEAR_CANDIDATES)  # per row: its frame
        w, dp, angle = pose_errors(np.array([self.frame_pose(f, near_full) for f in names])[code], X)
        far = angle + np.linalg.norm(dp, axis=1) / NEAR_METRES_PER_RAD
        if self.batch is not None:  # the joint motion the pose change asks at first order: |J+ (w; dp)|
            inverse = np.array([self._jacobian_inverse(f, near_full) for f in names])
            far = np.linalg.norm(np.einsum("bij,bj->bi", inverse[code], np.concatenate([w, dp], axis=1)), axis=1)
        far = far.reshape(len(j), NEAR_CANDIDATES)
        keep = np.arange(len(j)) * NEAR_CANDIDATES + np.argmin(far, axis=1)
        return V[keep], X[keep]

    def approach_shift(self, region: PoseRegion, scale: float) -> np.ndarray:
        """The pre-pose of a target X_WT is X_WT times this: ``scale`` x the approach, in the robot frame's axes."""
        shift = np.eye(4)
        shift[:3, 3] = scale * self._table.approach[self._index[region.id]]
        return shift

    def approach_from(self, region: PoseRegion, v: np.ndarray, q_full: np.ndarray, scale: float = 1.0) -> np.ndarray | None:
        """The pre-pose configuration for a goal at ``q_full``, if its straight approach is free.

        The pre-pose is ``scale`` times the region's approach away. It is solved
        from ``q_full`` so it stays on the same IK branch; the joint-space segment
        from it to the goal is collision-checked every APPROACH_RESOLUTION.
        """
        frame, X_pre = self.target_pose_for(region, v, approach=True, scale=scale)
        pre_full = self.solve(frame, X_pre, q_full)
        return None if pre_full is None else self._approach_free(pre_full[self.planned], q_full[self.planned])

    def _approach_free(self, pre: np.ndarray, q: np.ndarray) -> np.ndarray | None:
        """``pre`` if it is within the limits and the segment pre -> q (q known free) is free, else None.

        Checked every APPROACH_RESOLUTION, ``pre`` first (on fetch_boxes_3, 86-98 % of the blocked
        approaches are blocked there already): with the compiled certifier as one edge check with early
        exit (the end first, then bisection: ~0.1 ms an approach against ~0.2 ms in three batches, #31);
        without it, ``pre`` alone, then every fourth configuration (a blocked approach is usually blocked
        over several), then the rest, in batches.
        """
        if not self.world.space.within_bounds(pre):
            return None
        if self.world.edge_part_free is not None:
            return pre if self.world.edge_free(q, pre, APPROACH_RESOLUTION) else None
        path = self.world.space.discretize(pre, q, APPROACH_RESOLUTION)[:-1]
        coarse = np.zeros(len(path), bool)
        coarse[::4] = True
        coarse[0] = False
        for part in (path[:1], path[coarse], path[~coarse][1:]):
            if len(part) and not np.all(self.world.configs_free(part)):
                return None
        return pre

    def screen(self, frame: str, X_WT: np.ndarray) -> list[str]:
        """Why each target pose (B, 4, 4) of ``frame`` fails before any solve ("" for none): :class:`TargetScreen`."""
        return self.target_screen.reasons(frame, X_WT)

    def draw_preferred(self, regions: list[int], rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`draw_targets`, or with a preference (``prefer``) the preferred of its ``draws`` per attempt.

        The batch solver's attempts draw here; the one-at-a-time solvers (``snopt``, ``ipopt``) draw uniformly.
        """
        if self.prefer is None:
            return self.draw_targets(regions, rng)
        j = np.asarray(regions, int)
        V = self.prefer.pick(j, np.stack([self.draw_targets(regions, rng)[0] for _ in range(self.prefer.draws)]))
        return V, self.target_poses(j, V)

    def avoided(self, regions: list[int], V: np.ndarray) -> np.ndarray:
        """Which draws ``V`` (N, 6) of ``regions`` the preference rules out (a place to keep clear), (N,) bool."""
        if self.prefer is None:
            return np.zeros(len(V), bool)
        return np.asarray(self.prefer.avoided(np.asarray(regions, int), np.asarray(V, float)), bool)

    # --- one attempt -------------------------------------------------------------------------
    def attempt(self, j: int, rng: np.random.Generator, stop: StopCondition) -> tuple[GoalSample | None, str]:
        if self.batch is not None:
            if self._stop(stop).should_stop():  # the stop first: a zero budget is spent at once
                return None, "time"
            items = self.batch.prepare([(j, -1)], rng)
            self.batch.check(items)
            return self.learn(j, items[0].v, *self._finish(items[0]))
        region = self.regions[j]
        v = from_unit(*region.unit_map(), self.learner.warp([j], rng.random((1, len(region.lower))))[0])  # region.sample's draws
        frame, X_WT = self.target_pose_for(region, v)
        reason = self.screen(frame, X_WT.matrix()[None])[0]
        if reason:
            return self.learn(j, v, None, reason)
        seeds = [self.last[j]] if self.last[j] is not None and self.settings.warm_start else []
        if self.near is not None and self.starts_near(j):
            seeds = [self.near_full()]
        item = Prepared(j, -1, v, frame, X_WT.matrix())
        return self.learn(j, v, *self._first_valid(
            item, stop, lambda k: self.solve(frame, X_WT, seeds[k] if k < len(seeds) else self.random_full(rng), counters=self.region_counters[j]),
            lambda k, q_full, scale: self.approach_from(region, v, q_full, scale)))

    def learn(self, j: int, v: np.ndarray, sample: GoalSample | None, reason: str) -> tuple[GoalSample | None, str]:
        """(sample, reason), after scoring the draw ``v`` of region ``j`` by it (:class:`RegionLearner`)."""
        score = outcome_score(reason, self.reached_reasons)
        if score is not None:
            self.learner.record(j, v, score)
        return sample, reason

    def _stop(self, stop: StopCondition) -> StopCondition:
        """One attempt's stop condition: ``attempt_budget`` seconds of ``stop``'s time."""
        budget = self.settings.attempt_budget
        return stop if budget is None else stop.share(seconds=budget)

    def _first_valid(self, item: Prepared, stop: StopCondition, answer: Callable, approach: Callable) -> tuple[GoalSample | None, str]:
        """The attempt's sample from its first restart whose answer is within the limits and free, or why none.

        ``answer(k)`` is restart k's IK answer (full positions) or None; ``approach(k, q_full, scale)``
        the pre-pose at ``scale`` of the approach for it, or None when blocked.
        """
        k, q_full, reason = self.grasp(item, answer, self._stop(stop))
        return (None, reason) if k is None else (self._sample(item, k, q_full, approach), "")

    def grasp(self, item: Prepared, answer: Callable, stop: StopCondition | None) -> tuple[int | None, np.ndarray | None, str]:
        """(restart, full positions, "") of the attempt's first answer within the limits and free, or (None, None, why not).

        ``answer(k)`` is restart k's IK answer (full positions) or None; no restart starts after ``stop``.
        """
        reason = "time"
        for k in range(self.settings.restarts):
            if stop is not None and stop.should_stop():
                break
            q_full = answer(k)
            if q_full is None:
                reason = "ik failed" if reason != "in collision" else reason
                continue
            q = q_full[self.planned]
            if not self.world.space.within_bounds(q):
                reason = "outside limits"
                continue
            if not self.world.config_free(q):
                reason = "in collision"  # another restart may find a collision-free branch
                continue
            return k, q_full, ""
        return None, None, reason

    def _sample(self, item: Prepared, k: int, q_full: np.ndarray, approach: Callable) -> GoalSample:
        """The goal sample of a free grasp ``q_full`` (restart k), aimed at the longest free approach."""
        j, region = item.j, self.regions[item.j]
        self.last[j] = q_full
        q = q_full[self.planned]
        extra = {"X_WG": Pose.from_matrix(item.X_WT), "v": item.v, "frame": item.frame}
        # Aim at a pre-pose when its straight approach is free: the full distance, then
        # shorter ones; under a low shelf board only the goal itself may be left.
        for scale in APPROACH_SCALES if any(region.approach) else ():
            pre = approach(k, q_full, scale)
            if pre is not None:
                shift = self._nearest_turns(q, pre)
                return GoalSample(q=pre + shift, region=j, final=q + shift, extra=extra | {"approach_scale": scale})
        return GoalSample(q=q + self._nearest_turns(q), region=j, extra=extra)

    def seed_near(self) -> bool:
        """Every attempt solved from ``near`` alone from now on: goals on the IK branch nearest the start (an
        attempt whose solve from there fails fails: other restarts would land on other branches)."""
        if self.near is None:
            return False
        self.settings = replace(self.settings, seed_near=True, near_targets=True, restarts=1)
        if self.batch is not None:
            self.batch.queue.clear()  # answers solved before came from other starts
        return True

    def _jacobian_inverse(self, frame: str, q_full: np.ndarray) -> np.ndarray:
        """The pseudo-inverse (n, 6) of ``frame``'s Jacobian over its chain at ``q_full`` (held joints' columns zero)."""
        problem = self.batch.solver.problems[frame]
        _, J = problem.chain.forward(q_full[problem.chain.index][None], jacobian=True)
        return np.linalg.pinv(J[0] * problem.free)

    def starts_near(self, j: int) -> bool:
        """Whether region ``j``'s first restart starts from ``near`` (given one): always under ``seed_near``;
        under ``near_first`` while the region has no valid sample (its first goal on the branch nearest the start)."""
        return self.settings.seed_near or (self.settings.near_first and self.stats[j].valid == 0)

    def near_full(self) -> np.ndarray | None:
        """Full plant positions at ``near`` (the step's start), or None without one."""
        if self.near is None:
            return None
        q = self.world.q_full.copy()
        q[self.planned] = self.near
        return q

    def _nearest_turns(self, q: np.ndarray, *together: np.ndarray) -> np.ndarray:
        """Full turns taking goal ``q`` (and its pre-pose) nearest the start: the same grasp, a shorter motion (#28)."""
        if self._turns is None or not self._turns.any() or self.near is None:
            return np.zeros_like(q)
        space = self.world.space
        return nearest_turns(q, self.near, space.lower, space.upper, self._turns, together)

    # --- many attempts at once (solver "batch") ----------------------------------------------
    def batch_size(self, wanted: int) -> int:
        # The whole draw's budget is planned; attempts() solves it a look-ahead at a time, lazily.
        self.wanted = wanted
        return 1 if self.batch is None else wanted * self.attempts_per_sample

    def attempts(self, plan, rng, stop):
        if self.batch is None:
            yield from super().attempts(plan, rng, stop)
            return
        for i, (j, after) in enumerate(plan):
            item = self.batch.take(j, after, plan[i - 1][1] if i else self.next_region, rng, lambda i=i: self._look_ahead(len(plan) - i))
            a0 = stop.now()
            sample, reason = self.learn(j, item.v, *self._finish(item))
            self.wanted -= sample is not None
            yield sample, reason, item.seconds + stop.now() - a0

    def _look_ahead(self, left: int) -> int:
        """How many attempts to solve at once: enough for the samples the draw still wants at the
        success rate so far (prior 1 in 8), half as many again, within [LOOK_AHEAD_MIN, batch_attempts],
        and never more than the ``left`` attempts the draw's budget still allows.

        Bigger batches cost less per solve (one iteration's numpy overhead is shared), but what a
        plan never draws is wasted: a fixed 64 left ~1/3 of the solves unused on fetch_cans_1, and
        a look-ahead past the draw's budget was solved for a draw that may never come. The prior
        errs on the large side: an attempt solved in vain costs only its rows of the batch (grasp
        checks and pre-poses wait for the draw, BatchAttempts.check), one too few a second batch of
        ~15 iterations. With 1 in 4, fetch_boxes_3 (~1 in 12) solved its first draw in two batches
        (CPU ms per goal sample 5.6 against 4.6 with 1 in 8, seeds 20-79; /tmp/notes/ik6.md).
        """
        valid, attempts = self.total_valid, self.total_attempts
        rate = (valid + 1) / (attempts + 8)
        need = math.ceil(1.5 * max(self.wanted, 1) / rate)
        return int(min(max(need, LOOK_AHEAD_MIN), max(self.settings.batch_attempts, 1), max(left, LOOK_AHEAD_MIN)))

    def _finish(self, item: Prepared) -> tuple[GoalSample | None, str]:
        """An attempt's sample from its prepared answer, grasp check and pre-poses: only the approach is checked here."""
        if item.reason:
            return None, item.reason

        def approach(k, q_full, scale):
            answers, ok = item.pre[k]
            i = APPROACH_SCALES.index(scale)
            return self._approach_free(answers[i][self.planned], q_full[self.planned]) if ok[i] else None

        return self._sample(item, item.k, item.answers[item.k], approach), ""

    def solve(self, frame: str, X_WT: Pose, seed_full: np.ndarray, counters: IKCounters | None = None) -> np.ndarray | None:
        """Full plant positions putting ``frame`` at ``X_WT`` (within tolerance) by one Drake IK solve, or None.

        Args:
            frame: the robot frame to place.
            X_WT: its target world pose.
            seed_full: the initial guess (full plant positions; clipped to the limits).
            counters: a region's counters, counted besides the source's.

        Returns:
            the positions, judged by forward kinematics (not by the solver's status), or None.
        """
        t0 = time.perf_counter()
        q_sol = self.program.solve_pose(frame, X_WT.matrix(), seed_full)
        dt = time.perf_counter() - t0
        for c in (self.counters, counters):
            if c is not None:
                c.add(1, int(q_sol is not None), dt)
        return q_sol

    # --- kinematics helpers ------------------------------------------------------------------
    def frame_pose(self, frame: str, q_full: np.ndarray) -> np.ndarray:
        """World pose (4x4) of a frame at full plant positions ``q_full``."""
        return self._kinematics.matrix(frame, q_full)

    def pose_error(self, frame: str, q_full: np.ndarray, X_WT: Pose) -> tuple[float, float]:
        """(position error in m, rotation angle in rad) of ``frame`` at ``q_full`` from ``X_WT``."""
        return pose_error(self._kinematics, frame, q_full, X_WT.matrix())

    def random_full(self, rng: np.random.Generator) -> np.ndarray:
        """Full plant positions with the planned ones drawn uniformly."""
        q = self.world.q_full.copy()
        q[self.planned] = self.world.space.sample(rng)
        return q


def region_coordinates(region: PoseRegion, X_WG: np.ndarray) -> np.ndarray:
    """The end-effector pose ``X_WG`` (4x4) as a 6-vector in the region's sampled frame (:meth:`PoseRegion.coordinates_of`)."""
    return region.coordinates_of(X_WG)
