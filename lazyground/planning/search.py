"""One planning query's bookkeeping, shared by the tree planners.

The stop condition (:mod:`lazyground.planning.stop`), the goal samples drawn so far and the goal-selection
strategy over them (reward, penalty, resampling on demand), the counters, the
fine re-check of a candidate path, and the PlanResult.
"""

from __future__ import annotations

import numpy as np

from lazyground.planning.problem import (
    GoalSample,
    GoalSource,
    PlannerSettings,
    PlanResult,
    PlanStatus,
    ValidityChecker,
    proven_unreachable,
    unreachable_note,
)
from lazyground.planning.blocked import BlockedTrees
from lazyground.planning.motion_validator import MotionValidator, samples_free
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition
from lazyground.planning.strategies import StrategySettings, make_strategy
from lazyground.planning.tree import Tree


def path_is_valid(space: ConfigSpace, checker: ValidityChecker, path: np.ndarray, resolution: float,
                  segments: list[int] | None = None) -> int:
    """Index of the first invalid segment of ``path`` checked at ``resolution``, or -1.

    The segments' configurations go to the checker in one batch (one call into
    Drake instead of one per segment); a vertex shared by two checked segments
    is checked once. ``segments`` restricts the check to those segment indices
    (ascending; default all).
    """
    qs, owner = space.discretize_path(path, range(len(path) - 1) if segments is None else segments, resolution)
    if not len(qs):
        return -1
    blocked = np.flatnonzero(~samples_free(space, checker, qs))
    return int(owner[blocked[0]]) if len(blocked) else -1


# what one goal-sampling attempt in a region of each kind tries (issue 34: the status said "0/50 valid", not of what)
TRIED = {"workspace": "grasps", "placement": "placements"}


def _checks(checker: ValidityChecker) -> int:
    """The checker's check count (0 for a checker that does not count)."""
    return int(getattr(checker, "checks", 0))


class Search:
    def __init__(
        self,
        space: ConfigSpace,
        checker: ValidityChecker,
        goals: GoalSource,
        settings: PlannerSettings,
        rng: np.random.Generator,
        seed: int | None,
        keep_tree: bool,
        stop: StopCondition | None = None,
        setup_s: float = 0.0,
    ):
        self.space, self.checker, self.goals, self.settings, self.rng = space, checker, goals, settings, rng
        if stop is None:  # the settings' own limits, from now
            stop = StopCondition.after(settings.time_limit, max_iterations=settings.max_iterations)
        self.seed, self.keep_tree, self.stop = seed, keep_tree, stop
        self.motion = space.motion_validator(checker)  # edges as the space moves along them (OMPL's MotionValidator)
        # the validator of straight edges forwards to the checker's edge check: the loop calls that directly (#31)
        self.edge_free = checker.edge_free if type(self.motion) is MotionValidator else self.motion.edge_free
        # read once, not per step (#31): the edge spacing and the probe a lazy step asks (penetration only where
        # the checker has it)
        self.resolution = settings.resolution
        self.probe_free = getattr(checker, "config_unpadded_free", checker.config_free)
        # a Reeds-Shepp car's straight drive (birrt._extend, birrt._shut_in)
        self.straight_step = space.straight_step if getattr(space, "drives_straight", False) else None
        self.t0 = stop.now() - setup_s  # the goal source's making counts (rrt.solve's setup_s)
        self.setup_s = setup_s
        self._check_t0, self._sample_t0 = checker.check_time, goals.sample_time
        self._sampling_checks = 0.0  # collision checks made by the goal sampler count as goal sampling
        self._checks0, self._sampling_count = _checks(checker), 0
        self.samples: list[GoalSample] = []
        self.dead: set[int] = set()  # samples whose approach segment failed the fine re-check (retire())
        self._below: set[int] = set()  # live samples whose weight is below the resampling threshold
        self._verified: set[bytes] = set()  # segments (endpoint bytes) that passed the fine re-check
        self.selector = make_strategy(settings.strategy, StrategySettings(resample_threshold=settings.resample_threshold))
        self._covers = bool(getattr(self.selector, "covers_regions", False))
        chooser = getattr(self.selector, "region_chooser", None)  # the strategy picks the regions samples come from
        if chooser is not None and hasattr(goals, "chooser"):
            goals.chooser = chooser(goals)
        # goal trees that cannot grow out of their root (lazyground.planning.blocked): tracked by a goal-forest
        # planner (track_blocked) where the strategy chose the regions (cover on IK goals); None elsewhere
        self.blocked: BlockedTrees | None = None
        # the regions coverage paces samples for: those not proven unreachable before the search (a reach prior)
        self._coverable = sum(not st.unreachable for st in goals.stats)
        self._attempts0: int | None = None  # the goal source's attempt count when coverage began
        self.trees: list[Tree] = []  # the planner's trees, start tree first (for the result)
        self.failed_from: list[tuple[int, int]] = []  # (tree, node) of failed goal-directed extensions
        self.iterations = self.resamplings = self.rejected = 0

    def track_blocked(self) -> None:
        """Count the goal trees that stay their root (a planner with a goal forest calls it before its first
        sample) where the strategy chose the regions and has a ``blocked_after``; else nothing changes."""
        after, chooser = getattr(self.selector, "blocked_after", 0), getattr(self.goals, "chooser", None)
        if after and chooser is not None:  # (the chooser hears of them: a blocked or aged sample counts as a miss)
            tell, age = getattr(chooser, "block_sample", None), getattr(chooser, "age_sample", None)
            self.blocked = BlockedTrees(after, None if tell is None else
                                        lambda gi, blocked: tell(self.samples[gi].region, blocked),
                                        getattr(self.selector, "age_after", 0),
                                        None if age is None else lambda gi: age(self.samples[gi].region))

    def time_left(self) -> bool:
        """Whether the stop condition lets the search go on (one clock reading)."""
        return not self.stop.should_stop(self.iterations)

    def draw(self, n: int) -> None:
        """Draw up to n more goal samples and hand them to the strategy."""
        c0, n0 = self.checker.check_time, _checks(self.checker)
        new = self.goals.draw(n, self.rng, self.stop)
        for sample in new:  # the planner's own vector: the compiled steps of its trees take no read-only or strided one
            sample.q = np.array(sample.q, float)
        self._sampling_checks += self.checker.check_time - c0
        self._sampling_count += _checks(self.checker) - n0
        first = len(self.samples)
        self.samples.extend(new)
        self.selector.add(list(range(first, len(self.samples))))
        if self._below:  # (reward-penalty resets the old weights when it adds)
            self._below = {i for i in self._below if self.selector.weight(i) < self.settings.resample_threshold}

    def have_samples(self) -> bool:
        """Whether any goal sample exists yet; draws a batch when none does.

        A strategy that paces coverage (``covers_regions``) gets one more sample each iteration
        until there are as many samples as goal regions not proven unreachable (lazyground.planning.cover)."""
        if not self.samples:
            self.draw(self.settings.initial_goal_samples)
        elif self._covers and len(self.samples) < self._coverable and self._ik_in_budget():
            self.draw(1)
        return bool(self.samples)

    def _ik_in_budget(self) -> bool:
        """Whether goal sampling is within the strategy's budget: the goal source's attempts since the first
        sample at most the strategy's ``ik_allowance(iterations)`` (a strategy or source without one: always).

        Counted, not timed, so that a seed gives the same run on any machine."""
        total = getattr(self.goals, "total_attempts", None)
        allowance = getattr(self.selector, "ik_allowance", None)
        if total is None or allowance is None:
            return True
        if self._attempts0 is None:
            self._attempts0 = total
        if self.blocked is not None:  # (whether a goal tree can still grow: lazyground.planning.blocked)
            return total - self._attempts0 <= allowance(self.iterations, self.blocked.live > 0)
        return total - self._attempts0 <= allowance(self.iterations)

    def select(self) -> int | None:
        """The strategy's goal sample (skipping dead ones), its attempt counted; None if all are dead."""
        for _ in range(len(self.samples)):
            gi = self.selector.select(self.rng)
            if gi not in self.dead:
                self.samples[gi].attempts += 1
                return gi
            self.penalize(gi)
        self.draw(self.settings.resample_count)
        return None

    def reward(self, gi: int) -> None:
        self.samples[gi].rewards += 1
        self.selector.reward(gi)
        if self.selector.weight(gi) >= self.settings.resample_threshold:
            self._below.discard(gi)

    def retire(self, gi: int) -> None:
        """Goal sample gi's approach failed the fine re-check: never select it again."""
        self.dead.add(gi)
        self._below.discard(gi)
        if self.blocked is not None:
            self.blocked.retire(gi)

    def penalize(self, gi: int, only_if_all_stuck: bool = False) -> None:
        """Count a failure of goal sample gi; draw more samples when the strategy asks for them
        (with ``only_if_all_stuck``, only once every live sample's weight is below the threshold)."""
        self.samples[gi].penalties += 1
        wants_more = self.selector.penalize(gi)
        if gi not in self.dead and self.selector.weight(gi) < self.settings.resample_threshold:
            self._below.add(gi)
        if wants_more and only_if_all_stuck and not getattr(self.selector, "resample_alone", False):
            wants_more = len(self._below) >= len(self.samples) - len(self.dead)  # every live sample is stuck (no scan)
        if wants_more and self._covers:
            wants_more = self._ik_in_budget()
        if wants_more:
            self.resamplings += 1
            self.draw(getattr(self.selector, "batch", self.settings.resample_count))

    def first_invalid_segment(self, path: np.ndarray) -> int:
        """The fine re-check every returned path passes (-1: valid); counts rejections.

        A segment that passed an earlier re-check in this query is not checked again
        (a rejected join leaves most of its segments valid, and the next candidate
        path usually shares them).
        """
        rows = [q.tobytes() for q in path]  # (each vertex once: it ends one segment and starts the next)
        keys = [rows[k] + rows[k + 1] for k in range(len(path) - 1)]
        todo = [k for k, key in enumerate(keys) if key not in self._verified]
        bad = path_is_valid(self.space, self.checker, path, self.settings.resolution / self.settings.validation_factor, todo)
        self._verified.update(keys[k] for k in todo if bad < 0 or k < bad)
        self.rejected += bad >= 0
        return bad

    def with_approach(self, path: np.ndarray, gi: int) -> np.ndarray:
        """The path with the sample's checked approach segment appended, if it has one."""
        final = self.samples[gi].final
        return path if final is None else np.vstack([path, final])

    def result(self, status: PlanStatus, message: str = "", path=None, gi: int | None = None) -> PlanResult:
        for i, sample in enumerate(self.samples):
            sample.weight = self.selector.weight(i)
        goal = self.samples[gi] if gi is not None else None
        length = self.space.path_length(path) if path is not None else 0.0
        if path is not None:  # as the robot moves along it (a car: its curves, densely)
            path = self.space.dense_path(path)
        return PlanResult(
            status=status,
            seed=self.seed,
            path=path,
            goal=goal,
            goal_region=self.goals.regions[goal.region] if goal is not None else None,
            iterations=self.iterations,
            tree_size=sum(len(t) for t in self.trees),
            goal_samples=self.samples,
            resamplings=self.resamplings,
            time_s=self.stop.now() - self.t0,
            goal_sampling_s=self.goals.sample_time - self._sample_t0 + self.setup_s,
            collision_s=self.checker.check_time - self._check_t0 - self._sampling_checks,
            message=message,
            regions=tuple(self.goals.regions),
            region_stats=list(self.goals.stats),
            tree=self._tree_arrays() if self.keep_tree else None,
            failed_from=self._failed_from() if self.keep_tree else None,
            path_length=length,
            invalid_paths_rejected=self.rejected,
            collision_checks=_checks(self.checker) - self._checks0 - self._sampling_count,
        )

    def region_summary(self) -> str:
        """Each goal region's tries (grasps, placements or configurations), valid ones, and why the others failed."""
        parts = []
        proven = unreachable_note(self.goals.regions, self.goals.stats)
        for region, st in zip(self.goals.regions, self.goals.stats):
            if st.unreachable:
                continue
            why = ", ".join(f"{k} x{v}" for k, v in sorted(st.failures.items()))
            tried = f"{st.attempts} {TRIED.get(region.kind, 'configurations')} tried, {st.valid} valid"
            parts.append(f"{region.id}: {tried} ({why})" if why else f"{region.id}: {tried}" if st.attempts else f"{region.id}: not tried")
        return "; ".join(parts + ([proven] if proven else []))

    def no_goal(self) -> PlanResult:
        _, n, why = proven_unreachable(self.goals.regions, self.goals.stats)
        if why and all(st.unreachable for st in self.goals.stats):  # one line, not a list of untried regions
            return self.result(PlanStatus.NO_VALID_GOAL, f"no reachable goal: all {n} interpretation(s) proven unreachable "
                               f"by the {why} (a disc or ball inside the robot's body has no way there from the start)")
        return self.result(PlanStatus.NO_VALID_GOAL, "no valid goal configuration in any goal region: " + self.region_summary())

    def _offsets(self) -> list[int]:
        return list(np.cumsum([0] + [len(t) for t in self.trees[:-1]]))

    def _tree_arrays(self):
        """All trees as one node list; goal-tree nodes count as goal-directed (flag True)."""
        if not self.trees:
            return None
        nodes, parents, flags = [], [], []
        for k, (t, off) in enumerate(zip(self.trees, self._offsets())):
            n, p, g = t.arrays()
            nodes.append(n)
            parents.append(np.where(p >= 0, p + off, -1))
            flags.append(g | (k > 0))
        return np.vstack(nodes), np.concatenate(parents), np.concatenate(flags)

    def _failed_from(self) -> np.ndarray:
        off = self._offsets() if self.trees else [0]
        return np.array([off[t] + i for t, i in self.failed_from], int)
