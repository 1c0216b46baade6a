"""The tree-based planner of Algorithm 1 with pluggable goal selection.

Hernández, Moll and Kavraki, "Lazy Evaluation of Goal Specifications Guided by
Motion Planning", ICRA 2019: an RRT whose goal-biased extensions go towards
goal samples chosen by a strategy (reward-penalty max-heap, consecutive, or
random), drawing more goal samples on demand (Sec. III-C).
"""

from __future__ import annotations

import time

import numpy as np

from lazyground.planning.nn import NearestNeighbors
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


def path_is_valid(space: ConfigSpace, checker: ValidityChecker, path: np.ndarray, resolution: float) -> int:
    """Index of the first invalid segment of ``path`` checked at ``resolution``, or -1."""
    for k in range(len(path) - 1):
        if not np.all(checker.configs_free(space.discretize(path[k], path[k + 1], resolution))):
            return k
    return -1


class _Tree:
    """Nodes, parents and a nearest-neighbour index over the space's embedding."""

    def __init__(self, space: ConfigSpace, root: np.ndarray):
        self.space = space
        self.nodes = [np.asarray(root, float)]
        self.parents = [-1]
        self.goal_biased = [False]
        self.nn = NearestNeighbors(space.embed_dim)
        self.nn.add(space.embed(root))

    def __len__(self) -> int:
        return len(self.nodes)

    def add(self, q: np.ndarray, parent: int, goal_biased: bool) -> int:
        self.nodes.append(q)
        self.parents.append(parent)
        self.goal_biased.append(goal_biased)
        return self.nn.add(self.space.embed(q))

    def nearest(self, q: np.ndarray) -> int:
        return self.nn.nearest(self.space.embed(q))

    def path_to(self, i: int) -> np.ndarray:
        idx = []
        while i >= 0:
            idx.append(i)
            i = self.parents[i]
        return np.array([self.nodes[j] for j in reversed(idx)])

    def prune(self, i: int) -> None:
        """Drop node i and its descendants from nearest-neighbour queries."""
        dead = {i}
        for j in range(i + 1, len(self.parents)):  # children always come after parents
            if self.parents[j] in dead:
                dead.add(j)
        self.nn.remove(sorted(dead))

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return np.array(self.nodes), np.array(self.parents), np.array(self.goal_biased)


def solve(
    space: ConfigSpace,
    checker: ValidityChecker,
    goals: GoalSource,
    start: np.ndarray,
    settings: PlannerSettings,
    rng: np.random.Generator,
    seed: int | None = None,
    keep_tree: bool = False,
) -> PlanResult:
    """Plan from ``start`` to any goal region of ``goals``.

    Args:
        space: the configuration space (metric, interpolation, bounds).
        checker: configuration validity; edges are checked by discretising at
            ``settings.resolution``.
        goals: lazily samples valid goal configurations from the goal regions.
        start: the start configuration.
        settings: planner settings.
        rng: the only source of randomness.
        seed: recorded in the result (the caller made ``rng`` from it).
        keep_tree: keep the tree and failed-extension origins for visualisation.

    Returns:
        A PlanResult; its status says whether a path was found. Every returned
        path has been re-checked at ``settings.resolution / validation_factor``.
    """
    t0 = time.perf_counter()
    deadline = t0 + settings.time_limit
    check_t0, sample_t0 = checker.check_time, goals.sample_time
    sampling_checks = [0.0]  # collision checks made by the goal sampler count as goal sampling, not twice
    start = np.asarray(start, float)
    samples: list[GoalSample] = []
    selector = make_strategy(
        settings.strategy, StrategySettings(resample_threshold=settings.resample_threshold)
    )
    tree = _Tree(space, start)
    failed_from: list[int] = []
    iterations = resamplings = rejected = 0

    def result(status: PlanStatus, message: str = "", path=None, goal=None) -> PlanResult:
        for i, sample in enumerate(samples):
            sample.weight = selector.weight(i)
        return PlanResult(
            status=status,
            seed=seed,
            path=path,
            goal=goal,
            goal_region=goals.regions[goal.region] if goal is not None else None,
            iterations=iterations,
            tree_size=len(tree),
            goal_samples=samples,
            resamplings=resamplings,
            time_s=time.perf_counter() - t0,
            goal_sampling_s=goals.sample_time - sample_t0,
            collision_s=checker.check_time - check_t0 - sampling_checks[0],
            message=message,
            regions=tuple(goals.regions),
            region_stats=list(goals.stats),
            tree=tree.arrays() if keep_tree else None,
            failed_from=np.array(failed_from, int) if keep_tree else None,
            path_length=space.path_length(path) if path is not None else 0.0,
            invalid_paths_rejected=rejected,
        )

    def draw(n: int) -> None:
        c0 = checker.check_time
        new = goals.draw(n, rng, deadline)
        sampling_checks[0] += checker.check_time - c0
        first = len(samples)
        samples.extend(new)
        selector.add(list(range(first, len(samples))))

    if not space.within_bounds(start):
        return result(PlanStatus.INVALID_START, "start configuration is outside the joint limits")
    if not checker.config_free(start):
        return result(PlanStatus.INVALID_START, f"start configuration is in collision: {checker.explain(start)}")
    resolution = settings.resolution
    try:
        draw(settings.initial_goal_samples)
        while time.perf_counter() < deadline and iterations < settings.max_iterations:
            if not samples:  # nothing valid yet: keep sampling goals lazily until told it is hopeless
                if goals.exhausted():
                    return result(PlanStatus.NO_VALID_GOAL, _no_goal_message(goals))
                draw(settings.initial_goal_samples)
                continue
            iterations += 1
            goal_biased = rng.random() < settings.goal_bias
            if goal_biased:
                gi = selector.select(rng)
                q_towards = samples[gi].q
                samples[gi].attempts += 1
            else:
                q_towards = space.sample(rng)
            near = tree.nearest(q_towards)
            q_near = tree.nodes[near]
            q_new, reached = space.steer(q_near, q_towards, settings.step_size)
            if checker.edge_free(q_near, q_new, resolution):
                node = tree.add(q_new, near, goal_biased)
                if not goal_biased:
                    continue
                # "connect" keeps stepping towards the goal sample while the steps are free
                while settings.goal_extension == "connect" and not reached and time.perf_counter() < deadline:
                    q_next, r = space.steer(q_new, q_towards, settings.step_size)
                    if not checker.edge_free(q_new, q_next, resolution):
                        break
                    node, q_new, reached = tree.add(q_next, node, True), q_next, r
                samples[gi].rewards += 1
                selector.reward(gi)
                if reached:
                    path = tree.path_to(node)
                    if samples[gi].final is not None:  # the checked approach segment from the sample
                        path = np.vstack([path, samples[gi].final])
                    bad = path_is_valid(space, checker, path, resolution / settings.validation_factor)
                    if bad < 0:
                        return result(PlanStatus.SOLVED, "", path, samples[gi])
                    rejected += 1  # a thin obstacle slipped between edge checks: cut the branch
                    tree.prune(_node_on_path(tree, node, bad + 1))
            elif goal_biased:
                samples[gi].penalties += 1
                failed_from.append(near)
                if selector.penalize(gi):
                    resamplings += 1
                    draw(settings.resample_count)
    except KeyboardInterrupt:
        return result(PlanStatus.INTERRUPTED, "interrupted")
    if not samples:
        return result(PlanStatus.NO_VALID_GOAL, _no_goal_message(goals))
    return result(PlanStatus.TIMEOUT, f"no path within {settings.time_limit:g} s ({iterations} iterations)")


def _node_on_path(tree: _Tree, leaf: int, depth: int) -> int:
    """The node at ``depth`` along the root-to-``leaf`` path."""
    chain = []
    while leaf >= 0:
        chain.append(leaf)
        leaf = tree.parents[leaf]
    return list(reversed(chain))[depth]


def _no_goal_message(goals: GoalSource) -> str:
    parts = []
    for region, st in zip(goals.regions, goals.stats):
        why = ", ".join(f"{k} x{v}" for k, v in sorted(st.failures.items())) or "not tried"
        parts.append(f"{region.id}: {st.valid}/{st.attempts} valid ({why})")
    return "no valid goal configuration in any goal region: " + "; ".join(parts)
