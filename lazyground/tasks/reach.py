"""One-step tasks (pick, park): plan from the start to any goal region of the grounding."""

from __future__ import annotations

from lazyground.goals import goal_source_for
from lazyground.motion.post import post_process
from lazyground.planning.problem import unreachable_note
from lazyground.planning.rrt import solve
from lazyground.planning.stop import StopCondition
from lazyground.planning.turns import sweep_note
from lazyground.tasks.anytime import best_step, improvement_notes
from lazyground.tasks.car_space import planning_space
from lazyground.tasks.outcome import Outcome, Step


def make_goal_source(world, regions, sampling=None):
    """The goal sampler registered for these regions' kind (:func:`lazyground.goals.goal_source_for`)."""
    return goal_source_for(tuple(regions), world, sampling)


def run(scene, grounding, settings, rng, worlds, *, seed: int | None = None, keep_tree: bool = False,
        clock=None, spent: float = 0.0) -> Outcome:
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
        spent: seconds of the time limit used before the task (grounding), taken off its deadline.

    Returns:
        An Outcome with one step; its path shortened and timed (lazyground.motion) when solved.
    """
    world = worlds.get()
    planner = settings.planner
    worlds.warm_kernels(planner.kinematics)
    worlds.warm_goal_caches(world, settings.goal_sampling.reach_prior)
    setup_s = worlds.setup_s
    space = planning_space(scene, world.space, planner.kinematics)  # a car's curves, or world.space
    stop = StopCondition.after(planner.time_limit, max_iterations=planner.max_iterations, clock=clock, spent=spent)

    best = best_step(lambda source, within, setup_s: solve(space, world, source, world.start, planner, rng, seed=seed,
                                                           keep_tree=keep_tree, stop=within, setup_s=setup_s),
                     lambda regions: make_goal_source(world, regions, settings.goal_sampling),
                     tuple(grounding.goal_regions), space, world, world.start, planner, stop, rng,
                     finish=lambda result: post_process(space, world, result, settings, rng))  # shortened and timed
    result, motion = best.result, best.motion
    notes = world.model_notes + ((motion.note,) if motion is not None and motion.note else ())
    swept = sweep_note(motion.shortcut.path, world.space.names, world.space.wrap, world.coordinates.turns) \
        if motion is not None and result.solved else None
    proven = unreachable_note(result.regions, result.region_stats)  # "k of N interpretations proven unreachable ..."
    notes += ((swept,) if swept else ()) + ((proven,) if proven else ()) + improvement_notes(best)
    return Outcome(result, (Step(grounding.action, result, setup_s, motion=motion),), world.space.names, notes,
                   improvements=best.improvements)
