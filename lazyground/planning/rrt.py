"""The tree-based planner of Algorithm 1 with pluggable goal selection.

Hernández, Moll and Kavraki, "Lazy Evaluation of Goal Specifications Guided by
Motion Planning", ICRA 2019: an RRT whose goal-biased extensions go towards
goal samples chosen by a strategy (reward-penalty max-heap, consecutive, or
random), drawing more goal samples on demand (Sec. III-C).
``Algorithm.BIDIRECTIONAL`` runs the two-tree variant instead
(:mod:`lazyground.planning.birrt`).
"""

from __future__ import annotations

import numpy as np

from lazyground.planning.birrt import grow_bidirectional
from lazyground.planning.problem import GoalSource, PlannerSettings, PlanResult, PlanStatus, ValidityChecker
from lazyground.planning.search import Search, path_is_valid
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition, StopReason
from lazyground.planning.tree import Tree
from lazyground.settings import Algorithm, GoalExtension

# What to try when an algorithm times out with goals in hand (issue 34: the README's one-tree line timed out with no hint).
TRY_INSTEAD = {Algorithm.RRT: f"; the two-tree planner often finds one sooner: try --algorithm {Algorithm.BIDIRECTIONAL}"}

__all__ = ["ALGORITHMS", "path_is_valid", "solve"]


def solve(
    space: ConfigSpace,
    checker: ValidityChecker,
    goals: GoalSource,
    start: np.ndarray,
    settings: PlannerSettings,
    rng: np.random.Generator,
    seed: int | None = None,
    keep_tree: bool = False,
    stop: StopCondition | None = None,
    setup_s: float = 0.0,
) -> PlanResult:
    """Plan from ``start`` to any goal region of ``goals``.

    Args:
        space: the configuration space (metric, interpolation, bounds).
        checker: configuration validity; edges are checked by discretising at
            ``settings.resolution``.
        goals: lazily samples valid goal configurations from the goal regions.
        start: the start configuration.
        settings: planner settings (``algorithm``: a key of :data:`ALGORITHMS`).
        rng: the only source of randomness.
        seed: recorded in the result (the caller made ``rng`` from it).
        keep_tree: keep the trees and failed-extension origins for visualisation.
        stop: when to give up (default: ``settings.time_limit`` seconds from now and
            ``settings.max_iterations``); goal sampling shares it.
        setup_s: seconds already spent making ``goals`` on ``stop``'s clock (its grids, screens and priors),
            counted in the result's ``time_s`` and ``goal_sampling_s``: the user waited for them too.

    Returns:
        A PlanResult; its status says whether a path was found. Every returned
        path has been re-checked at ``settings.resolution / validation_factor``.
    """
    search = Search(space, checker, goals, settings, rng, seed, keep_tree, stop, setup_s)
    stop = search.stop
    start = np.asarray(start, float)
    if not space.within_bounds(start):
        return search.result(PlanStatus.INVALID_START, "start configuration is outside the joint limits")
    if not checker.config_free(start):
        return search.result(PlanStatus.INVALID_START, f"start configuration is in collision: {checker.explain(start)}")
    try:
        search.draw(settings.initial_goal_samples)
        found = ALGORITHMS[settings.algorithm](search, start)
        if found is not None:
            return found
    except KeyboardInterrupt:
        return search.result(PlanStatus.INTERRUPTED, "stopped by Ctrl-C")
    if stop.reason is StopReason.INTERRUPTED:
        return search.result(PlanStatus.INTERRUPTED, "stopped by Ctrl-C")
    if not search.samples and search.goals.exhausted():
        return search.no_goal()
    cap = stop.max_iterations
    within = (f"{cap} iterations (max_iterations)" if cap is not None and search.iterations >= cap
              else f"{stop.budget:g} s ({search.iterations} iterations)")
    if not search.samples:  # the limit came before goal sampling had tried every region: not proof there is no goal
        return search.result(PlanStatus.TIMEOUT, f"no valid goal configuration found within {within}: {search.region_summary()}")
    return search.result(PlanStatus.TIMEOUT, f"no path within {within}{TRY_INSTEAD.get(settings.algorithm, '')}")


def grow_rrt(s: Search, start: np.ndarray) -> PlanResult | None:
    """Algorithm 1: one tree from the start, goal-biased steps towards the selected goal sample."""
    space, motion, edge_free, settings, rng = s.space, s.motion, s.edge_free, s.settings, s.rng
    tree = Tree(space)
    tree.add_root(start)
    s.trees = [tree]
    resolution = settings.resolution
    blocked: set[tuple[int, int]] = set()  # (node, goal sample): goal step blocked at once, or its path rejected
    while s.time_left():
        if not s.have_samples():  # nothing valid yet: keep sampling goals lazily until told it is hopeless
            if s.goals.exhausted():
                return s.no_goal()
            continue
        s.iterations += 1
        gi = None
        if rng.random() < settings.goal_bias:
            gi = s.select()
            if gi is None:
                continue
            q_towards = s.samples[gi].q
        else:
            q_towards = space.sample(rng)
        near, q_new, reached = tree.nearest_steer(q_towards, settings.step_size)
        q_near = tree.nodes[near]
        if gi is not None and (near, gi) in blocked:
            q_new = None  # the same edge as before: its answer has not changed
        elif gi is not None and settings.goal_extension is GoalExtension.PARTIAL:
            # the authors' RRTGoalRegion: a blocked goal step keeps its free part and counts as progress
            t = motion.edge_fraction(q_near, q_new, resolution)
            if t < 1.0:
                reached = False
                q_new = space.interpolate(q_near, q_new, t) if t > 0.0 else None
        elif not edge_free(q_near, q_new, resolution):
            q_new = None
        if q_new is None:
            if gi is not None:
                blocked.add((near, gi))
                s.failed_from.append((0, near))
                s.penalize(gi)
            continue
        node = tree.add(q_new, near, gi is not None)
        if gi is None:
            continue
        # "connect" keeps stepping towards the goal sample while the steps are free
        while settings.goal_extension is GoalExtension.CONNECT and not reached and s.time_left():
            q_next, r = tree.steer(node, q_towards, settings.step_size)
            if not edge_free(q_new, q_next, resolution):
                break
            node, q_new, reached = tree.add(q_next, node, True), q_next, r
        s.reward(gi)
        if reached:
            chain = tree.chain(node)[::-1]  # root .. node
            path = s.with_approach(np.array([tree.nodes[i] for i in chain]), gi)
            bad = s.first_invalid_segment(path)
            if bad < 0:
                return s.result(PlanStatus.SOLVED, "", path, gi)
            if bad + 1 < len(chain):  # a thin obstacle slipped between edge checks: cut the branch
                tree.prune(chain[bad + 1])
                blocked.add((chain[bad], gi))  # and never step the same edge towards this sample again
            else:  # the sample's own approach segment
                s.retire(gi)
    return None


ALGORITHMS = {Algorithm.RRT: grow_rrt, Algorithm.BIDIRECTIONAL: grow_bidirectional}
