"""The best answer rather than the first (issue #30): keep planning after the first solution.

With ``objective: shortest`` (or ``fastest``) a step is planned, shortened and timed once as
usual; then, within ``budget`` seconds (default: as long again as the first solution's search took),
the best solution by its *shortened* path length (or trajectory duration) is kept, found in two ways:

1. One straight segment: goal samples solved by IK from the start (the branch nearest it; the
   task's ``near`` callable) for every region the first search sampled, and the first search's own
   samples, nearest first, each joined to the start or to a waypoint of the best path so far
   (:func:`joined_path`). Cheap, and on open tabletops it reaches the nearest goal in a line.
2. Further searches (at most ``improve_rounds``; the task's ``search``, goals from the start) to
   the regions with a known goal sample that can still win, those not reached yet first. Each gets
   at most half of what is left of the budget, so an unreachable region cannot take all of it.

Pruning: a region whose nearest known goal sample is, in a straight line from the start, at
least as far as the best shortened path is dropped (the straight line bounds every path to that
sample; other samples of the region may be nearer, so it is a heuristic bound, as cuRobo's goalset
costs are). :func:`best_step` does the same for one step of a longer task (pick and place).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from lazyground.planning.problem import GoalSample, PlanResult, PlanStatus
from lazyground.planning.rrt import path_is_valid
from lazyground.planning.stop import StopCondition
from lazyground.regions import GoalRegion
from lazyground.settings import Objective, PlannerSettings

Attempt = Callable[[tuple[GoalRegion, ...], StopCondition], tuple[PlanResult, object]]
Connect = Callable[[PlanResult, GoalSample], tuple[PlanResult, object] | None]  # (solved template, goal sample)
Near = Callable[[tuple[GoalRegion, ...], int, StopCondition], list[GoalSample]]  # (regions, how many, stop)
JOIN_TRIES = 3  # waypoints of the best path a goal sample is joined to at most (joined_path)
NEAR_SAMPLES = 4  # goal samples solved from the start, at least one per region asked (each ~10-20 ms on a tabletop)


@dataclass(frozen=True)
class Improvement:
    """One better solution: seconds since the step began, its cost, the goal region it reached."""

    time_s: float
    cost: float
    region: str

    def to_json(self) -> dict:
        return {"time_s": round(self.time_s, 6), "cost": round(self.cost, 6), "region": self.region}


@dataclass(frozen=True)
class Anytime:
    """What :func:`best_of` returns: the best attempt, the improvements in time order and notes."""

    result: PlanResult
    motion: object | None
    improvements: tuple[Improvement, ...]
    searches: int
    pruned: tuple[str, ...]  # regions dropped because their bound could not beat the best


def cost(objective: Objective, result: PlanResult, motion) -> float:
    """A solved result's cost: its (shortened) path length, or its trajectory's duration for ``fastest``."""
    if not result.solved:
        return math.inf
    if objective is Objective.FASTEST and motion is not None and getattr(motion, "trajectory", None) is not None:
        return float(motion.trajectory.duration)
    return float(result.path_length)


def _add_bounds(bounds: dict[str, float], space, start: np.ndarray, result: PlanResult) -> None:
    """Per region id: the straight-line distance from the start to its nearest known goal sample (updated)."""
    for s in result.goal_samples:
        rid = result.regions[s.region].id
        bounds[rid] = min(bounds.get(rid, math.inf), space.distance(start, s.end))


def _straight_length(space, start: np.ndarray, sample: GoalSample) -> float:
    """The shortest path to ``sample`` conceivable: the straight line to it, then its kept approach."""
    return space.distance(start, sample.q) + (0.0 if sample.final is None else space.distance(sample.q, sample.final))


def joined_path(space, checker, path: np.ndarray, sample: GoalSample, resolution: float, bound: float,
                tries: int = JOIN_TRIES) -> np.ndarray | None:
    """``path`` up to one of its waypoints, then a straight line to ``sample`` (and its approach), if one is free.

    Waypoints are tried by the length of the joined path (the start first when nearest), at most ``tries`` of
    them, while that length is below ``bound``; each new segment is checked every ``resolution``. The path to
    the best answer found so far leads around what blocks the straight line from the start (shelves), so a
    goal beside its end is often one free segment away from a waypoint of it.
    """
    path = np.asarray(path, float)
    head = np.concatenate([[0.0], np.cumsum([space.distance(a, b) for a, b in zip(path[:-1], path[1:])])])
    after = 0.0 if sample.final is None else space.distance(sample.q, sample.final)
    joins = sorted((head[k] + space.distance(path[k], sample.q) + after, k) for k in range(len(path) - 1))
    for length, k in joins[:tries]:
        if length >= bound:
            break
        segment = np.array([path[k], sample.q])
        if path_is_valid(space, checker, segment, resolution) < 0:
            tail = [sample.q] if sample.final is None else [sample.q, sample.final]
            return np.vstack([path[:k + 1], tail])
    return None


def best_of(attempt: Attempt, regions: tuple[GoalRegion, ...], space, start: np.ndarray,
            planner: PlannerSettings, stop: StopCondition, connect: Connect | None = None,
            near: Near | None = None, search: Attempt | None = None) -> Anytime:
    """Plan with ``attempt`` once, then keep the best of further attempts as ``planner.objective`` asks.

    Args:
        attempt: plans to some of the regions within a stop condition; returns the result (shortened) and its
            Motion (or None).
        regions: every goal region of the step.
        space: the planning space (its ``distance`` bounds a path from below).
        start: the step's start configuration.
        planner: ``objective``, ``budget`` and ``improve_rounds`` are read.
        stop: the step's stop condition (the budget is a share of it).
        connect: joins a goal sample to the best answer so far (given as the template; e.g. by
            :func:`joined_path`), or None when it cannot; returns the (shortened) result and Motion. It is tried
            on the goal samples the first search drew, nearest first, while a straight line to them could win.
        near: draws up to n goal samples of the given regions solved from the start (the IK branch nearest
            it; their ``region`` indexes the regions given); ``connect`` then tries the straight line to each,
            nearest first, before any further search.
        search: plans as ``attempt`` does, for the searches after the first (default ``attempt``; e.g. with
            goals solved from the start). They go to regions with a known goal sample that could still win,
            those not reached yet first; to the others only when none is left.

    Returns:
        An :class:`Anytime`; its result's counts sum every search; beyond the first, its ``time_s`` is the
        whole time since ``stop`` began (searches, straight lines and shortening them) less the shortening and
        timing of the motion returned (a report counts that as motion, as for ``first``).
    """
    first, motion = attempt(regions, stop)
    best = (first, motion)
    if not first.solved:
        return Anytime(first, motion, (), 1, ())
    objective = Objective(planner.objective)
    history = [Improvement(stop.elapsed(), cost(objective, first, motion), first.goal_region.id)]
    if objective is Objective.FIRST or planner.improve_rounds == 0:
        return Anytime(first, motion, tuple(history), 1, ())
    seconds = planner.budget if planner.budget is not None else first.time_s
    improve = stop.share(seconds=seconds)
    results, bounds = [first], {}
    _add_bounds(bounds, space, start, first)
    reached, tried, pruned = {first.goal_region.id}, set(), set()

    def straight(samples) -> None:
        """Straight lines to ``samples`` (nearest first) while one could beat the best; the nearest is tried even
        when the budget ran out while drawing them (one segment check and shortening: ~20 ms on a tabletop)."""
        nonlocal best
        for i, sample in enumerate(sorted(samples, key=lambda g: _straight_length(space, start, g))[:planner.improve_rounds]):
            if (i and improve.should_stop()) or _straight_length(space, start, sample) >= history[-1].cost:
                break
            # the best path so far, on the first search's result (its regions are every region, as samples index)
            out = connect(replace(first, path=best[0].path, path_length=best[0].path_length), sample)
            if out is not None and cost(objective, *out) < history[-1].cost - 1e-9:
                best = out
                history.append(Improvement(stop.elapsed(), cost(objective, *out), out[0].goal_region.id))

    if connect is not None:  # the cheapest better answers: one straight segment to a goal sample
        # goals solved from the start, of every region the first search sampled: whatever the bound its samples
        # (on random IK branches) give, the branch nearest the start may be far nearer; then every sample,
        # those the first search drew too, nearest first
        ask = tuple(r for r in regions if r.id in bounds)
        drawn = near(ask, max(NEAR_SAMPLES, len(ask)), improve) if near is not None and ask else []
        drawn = [replace(g, region=regions.index(ask[g.region])) for g in drawn]
        _add_bounds(bounds, space, start, replace(first, goal_samples=drawn))
        straight(drawn + list(first.goal_samples))
    for _ in range(planner.improve_rounds):
        if improve.should_stop():
            break
        best_cost = history[-1].cost
        # a path is at least as long as the straight line; a duration has no such bound here
        alive = [r for r in regions if objective is not Objective.SHORTEST or bounds.get(r.id, 0.0) < best_cost]
        pruned = {r.id for r in regions} - {r.id for r in alive}
        if not alive:
            break
        known = [r for r in alive if r.id in bounds]  # a goal sample exists: IK reaches it, not only in words
        fresh = [r for r in known if r.id not in reached and r.id not in tried]
        targets = tuple(fresh or known or alive)
        tried |= {r.id for r in fresh}
        result, m = (search or attempt)(targets, improve.share(0.5))
        results.append(result)
        _add_bounds(bounds, space, start, result)
        if result.status is PlanStatus.INTERRUPTED:
            break
        if not result.solved:
            continue
        reached.add(result.goal_region.id)
        c = cost(objective, result, m)
        if c < best_cost - 1e-9:
            best = (result, m)
            history.append(Improvement(stop.elapsed(), c, result.goal_region.id))
    result, motion = best
    # every search, straight line and their shortening but the returned motion's own (the report counts it as motion)
    own = 0.0 if motion is None else getattr(motion, "shortcut_s", 0.0) + getattr(motion, "timing_s", 0.0)
    total = replace(result, iterations=sum(r.iterations for r in results), tree_size=result.tree_size,
                    time_s=stop.elapsed() - own,
                    goal_sampling_s=sum(r.goal_sampling_s for r in results),
                    collision_s=sum(r.collision_s for r in results))
    return Anytime(total, motion, tuple(history), len(results), tuple(sorted(pruned)))


def improvement_notes(best: Anytime) -> tuple[str, ...]:
    """One note when later searches ran: how many, the cost before and after, what was pruned."""
    if best.searches <= 1:
        return ()
    first, last = best.improvements[0], best.improvements[-1]
    pruned = f"; pruned {', '.join(best.pruned)}" if best.pruned else ""
    return (f"best of {best.searches} searches: cost {first.cost:.3f} -> {last.cost:.3f} "
            f"({len(best.improvements) - 1} improvement(s)){pruned}",)


def best_step(plan: Callable[[object, StopCondition, float], PlanResult], source_for: Callable[[tuple[GoalRegion, ...]], object],
              regions: tuple[GoalRegion, ...], space, checker, start: np.ndarray, planner: PlannerSettings,
              stop: StopCondition, rng: np.random.Generator,
              finish: Callable[[PlanResult], tuple[PlanResult, object]] | None = None) -> Anytime:
    """:func:`best_of` for one step planned by ``plan`` over goal sources: the first search, goals solved from the
    start, straight segments joined by :func:`joined_path` and searches with goals from the start.

    Args:
        plan: plans the step to a goal source's goals within a stop condition, given the seconds the source took to
            make (``planning.rrt.solve``'s ``setup_s``: counted as the search's time).
        source_for: the goal source for some of the step's regions (its ``near``: the step's start).
        regions, space, start, planner, stop: as for :func:`best_of`.
        checker: checks the straight segments joining goal samples.
        rng: draws the goals solved from the start.
        finish: shortens (and times) a solved result, returning it and its Motion; None: raw paths are compared
            (a pick and place shortens its steps later).
    """
    resolution = planner.resolution / planner.validation_factor
    done = finish if finish is not None else (lambda result: (result, None))

    def attempt(rs, within, near=False):
        t0 = within.now()
        source = source_for(rs)  # (its set-up is the search's time: the user waits for it, #33)
        if near:
            source.seed_near()
        return done(plan(source, within, within.now() - t0))

    def near(rs, n, within):
        source = source_for(rs)
        return source.draw(n, rng, within) if source.seed_near() else []

    def connect(template, sample):
        path = joined_path(space, checker, template.path, sample, resolution, template.path_length) \
            if space.post_processing == "straight" else None
        if path is None:
            return None
        return done(replace(template, path=path, goal=sample, goal_region=template.regions[sample.region],
                            path_length=space.path_length(path)))

    return best_of(attempt, regions, space, start, planner, stop, connect, near,
                   search=lambda rs, within: attempt(rs, within, near=True))
