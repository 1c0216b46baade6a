"""One planning query's bookkeeping, shared by the tree planners.

The clock and deadline, the goal samples drawn so far and the goal-selection
strategy over them (reward, penalty, resampling on demand), the counters, the
fine re-check of a candidate path, and the PlanResult.
"""

from __future__ import annotations

import time

import numpy as np

from lazyground.planning.problem import (
    GoalSample,
    GoalSource,
    PlannerSettings,
    PlanResult,
    PlanStatus,
    ValidityChecker,
)
from lazyground.planning.space import ConfigSpace
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
    todo = range(len(path) - 1) if segments is None else segments
    chunks, owner, prev = [], [], None
    for k in todo:
        qs = space.discretize(path[k], path[k + 1], resolution, skip_first=prev == k - 1)
        chunks.append(qs)
        owner.append(np.full(len(qs), k))
        prev = k
    if not chunks:
        return -1
    free = samples_free(space, checker, np.vstack(chunks))
    blocked = np.flatnonzero(~free)
    return int(np.concatenate(owner)[blocked[0]]) if len(blocked) else -1


# what one goal-sampling attempt in a region of each kind tries (issue 34: the status said "0/50 valid", not of what)
TRIED = {"workspace": "grasps", "placement": "placements"}


def samples_free(space: ConfigSpace, checker: ValidityChecker, qs: np.ndarray) -> np.ndarray:
    """Which configurations ``qs`` (samples along edges) are valid: inside the space's bounds and free.

    Nodes are sampled inside the bounds, and a straight edge between two stays inside them; a car's curve
    need not (issue 34: paths around walls at a lot's edge drove up to 6 m outside it), so every sample is
    held to the bounds where it is checked for collision."""
    qs = np.asarray(qs, float)
    inside = np.all((qs >= space.lower - 1e-9) & (qs <= space.upper + 1e-9), axis=1)
    if inside.all():
        return np.asarray(checker.configs_free(qs), bool)
    free = np.zeros(len(qs), bool)
    if inside.any():
        free[inside] = np.asarray(checker.configs_free(qs[inside]), bool)
    return free


def _checks(checker: ValidityChecker) -> int:
    """The checker's check count (0 for a checker that does not count)."""
    return int(getattr(checker, "checks", 0))


def edge_free(space: ConfigSpace, checker: ValidityChecker, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
    """Whether the edge a -> b is free: the checker's own edge check for straight edges,
    the space's samples along the curve otherwise (Drake's edge check interpolates linearly)."""
    if space.linear_edges:
        return checker.edge_free(a, b, resolution)
    return bool(np.all(samples_free(space, checker, space.discretize(a, b, resolution, skip_first=True))))


def edge_fraction(space: ConfigSpace, checker: ValidityChecker, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
    """The largest checked fraction t such that a -> interpolate(a, b, t) is free (the free prefix)."""
    if space.linear_edges:
        return checker.edge_fraction(a, b, resolution)
    qs = space.discretize(a, b, resolution, skip_first=True)
    blocked = np.flatnonzero(~samples_free(space, checker, qs))
    if not len(blocked):
        return 1.0
    if blocked[0] == 0:
        return 0.0
    # samples need not be evenly spaced (a car samples each segment on its own): the fraction of the
    # distance to the last free sample, which interpolate maps back to it (a shortest path's prefix
    # is the shortest path to its end)
    return space.distance(a, qs[blocked[0] - 1]) / space.distance(a, b)


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
    ):
        self.space, self.checker, self.goals, self.settings, self.rng = space, checker, goals, settings, rng
        self.seed, self.keep_tree = seed, keep_tree
        self.t0 = time.perf_counter()
        self.deadline = self.t0 + settings.time_limit
        self._check_t0, self._sample_t0 = checker.check_time, goals.sample_time
        self._sampling_checks = 0.0  # collision checks made by the goal sampler count as goal sampling
        self._checks0, self._sampling_count = _checks(checker), 0
        self.samples: list[GoalSample] = []
        self.dead: set[int] = set()  # samples whose approach segment failed the fine re-check
        self._verified: set[bytes] = set()  # segments (endpoint bytes) that passed the fine re-check
        self.selector = make_strategy(settings.strategy, StrategySettings(resample_threshold=settings.resample_threshold))
        self.trees: list[Tree] = []  # the planner's trees, start tree first (for the result)
        self.failed_from: list[tuple[int, int]] = []  # (tree, node) of failed goal-directed extensions
        self.iterations = self.resamplings = self.rejected = 0

    def time_left(self) -> bool:
        return time.perf_counter() < self.deadline and self.iterations < self.settings.max_iterations

    def draw(self, n: int) -> None:
        """Draw up to n more goal samples and hand them to the strategy."""
        c0, n0 = self.checker.check_time, _checks(self.checker)
        new = self.goals.draw(n, self.rng, self.deadline)
        self._sampling_checks += self.checker.check_time - c0
        self._sampling_count += _checks(self.checker) - n0
        first = len(self.samples)
        self.samples.extend(new)
        self.selector.add(list(range(first, len(self.samples))))

    def have_samples(self) -> bool:
        """Whether any goal sample exists yet; draws a batch when none does."""
        if not self.samples:
            self.draw(self.settings.initial_goal_samples)
        return bool(self.samples)

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

    def penalize(self, gi: int, only_if_all_stuck: bool = False) -> None:
        """Count a failure of goal sample gi; draw more samples when the strategy asks for them
        (with ``only_if_all_stuck``, only once every live sample's weight is below the threshold)."""
        self.samples[gi].penalties += 1
        wants_more = self.selector.penalize(gi)
        if wants_more and only_if_all_stuck:
            threshold = self.settings.resample_threshold
            wants_more = all(self.selector.weight(i) < threshold for i in range(len(self.samples)) if i not in self.dead)
        if wants_more:
            self.resamplings += 1
            self.draw(self.settings.resample_count)

    def first_invalid_segment(self, path: np.ndarray) -> int:
        """The fine re-check every returned path passes (-1: valid); counts rejections.

        A segment that passed an earlier re-check in this query is not checked again
        (a rejected join leaves most of its segments valid, and the next candidate
        path usually shares them).
        """
        keys = [path[k].tobytes() + path[k + 1].tobytes() for k in range(len(path) - 1)]
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
        length, cusps = (self.space.path_length(path) if path is not None else 0.0), None
        if path is not None and not self.space.linear_edges:  # a car: return the curves it drives, densely
            path = self.space.densify(path)
            cusps = self.space.cusps(path)
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
            time_s=time.perf_counter() - self.t0,
            goal_sampling_s=self.goals.sample_time - self._sample_t0,
            collision_s=self.checker.check_time - self._check_t0 - self._sampling_checks,
            message=message,
            regions=tuple(self.goals.regions),
            region_stats=list(self.goals.stats),
            tree=self._tree_arrays() if self.keep_tree else None,
            failed_from=self._failed_from() if self.keep_tree else None,
            path_length=length,
            invalid_paths_rejected=self.rejected,
            collision_checks=_checks(self.checker) - self._checks0 - self._sampling_count,
            cusps=cusps,
        )

    def region_summary(self) -> str:
        """Each goal region's tries (grasps, placements or configurations), valid ones, and why the others failed."""
        parts = []
        for region, st in zip(self.goals.regions, self.goals.stats):
            why = ", ".join(f"{k} x{v}" for k, v in sorted(st.failures.items()))
            tried = f"{st.attempts} {TRIED.get(region.kind, 'configurations')} tried, {st.valid} valid"
            parts.append(f"{region.id}: {tried} ({why})" if why else f"{region.id}: {tried}" if st.attempts else f"{region.id}: not tried")
        return "; ".join(parts)

    def no_goal(self) -> PlanResult:
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
