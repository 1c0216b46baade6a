"""One-step tasks (pick, park): plan from the start to any goal region of the grounding."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lazyground.goals import goal_source_for
from lazyground.motion.post import post_process
from lazyground.planning.rrt import solve
from lazyground.planning.stop import StopCondition
from lazyground.planning.turns import sweep_note
from lazyground.tasks.anytime import best_of, improvement_notes, joined_path
from lazyground.tasks.car_space import planning_space
from lazyground.tasks.outcome import Outcome, Step


def make_goal_source(world, regions, sampling=None):
    """The goal sampler registered for these regions' kind (:func:`lazyground.goals.goal_source_for`)."""
    return goal_source_for(tuple(regions), world, sampling)


def run(scene, grounding, settings, rng, worlds, *, seed: int | None = None, keep_tree: bool = False,
        clock=None) -> Outcome:
    """Plan to whichever of ``grounding``'s goal regions is reachable first, or the best one found within the
    budget (``objective``; :mod:`lazyground.tasks.anytime`).

    Args:
        scene: the Scene.
        grounding: the request's Grounding (its ``goal_regions``).
        settings: the run's RunSettings.
        rng: the only source of randomness.
        worlds: a :class:`~lazyground.tasks.worlds.Worlds` for ``scene``.
        seed: recorded in the result.
        keep_tree: keep the search tree (for viewers).
        clock: the clock the time limit is read on (default: the stop condition's).

    Returns:
        An Outcome with one step; its path shortened and timed (lazyground.motion) when solved.
    """
    world = worlds.get()
    setup_s = worlds.setup_s
    planner = settings.planner
    space = planning_space(scene, world.space, planner.kinematics)  # a car's curves, or world.space
    stop = StopCondition.after(planner.time_limit, max_iterations=planner.max_iterations, clock=clock)

    def attempt(regions, within, near=False):
        source = make_goal_source(world, regions, settings.goal_sampling)
        if near:
            source.seed_near()
        result = solve(space, world, source, world.start, planner, rng, seed=seed, keep_tree=keep_tree, stop=within)
        return post_process(space, world, result, settings, rng)  # shortened and timed, as the space chose

    def connect(template, sample):
        """The best path so far joined to a goal sample by one free straight segment (and its approach), if any."""
        if space.post_processing != "straight":
            return None
        path = joined_path(space, world, template.path, sample, planner.resolution / planner.validation_factor,
                           template.path_length)
        if path is None:
            return None
        result = replace(template, path=path, goal=sample, goal_region=template.regions[sample.region],
                         path_length=space.path_length(path))
        return post_process(space, world, result, settings, rng)

    def near(regions, n, within):
        """Up to ``n`` goal samples of ``regions`` solved from the start (none where the goal source cannot)."""
        source = make_goal_source(world, regions, settings.goal_sampling)
        return source.draw(n, rng, within) if source.seed_near() else []

    best = best_of(attempt, tuple(grounding.goal_regions), space, world.start, planner, stop, connect, near,
                   search=lambda regions, within: attempt(regions, within, near=True))
    result, motion = best.result, best.motion
    notes = world.model_notes + ((motion.note,) if motion is not None and motion.note else ())
    swept = sweep_note(motion.shortcut.path, world.space.names, world.space.wrap, world.coordinates.turns) \
        if motion is not None and result.solved else None
    notes += ((swept,) if swept else ()) + improvement_notes(best)
    return Outcome(result, (Step(grounding.action, result, setup_s, motion=motion),), world.space.names, notes,
                   improvements=best.improvements)
