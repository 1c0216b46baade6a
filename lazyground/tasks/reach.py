"""One-step tasks (pick, park): plan from the start to any goal region of the grounding."""

from __future__ import annotations

from lazyground.goals import goal_source_for
from lazyground.motion.car_shortcut import shorten_car_result, with_car_shortcut
from lazyground.motion.pipeline import motion_for_world
from lazyground.planning.rrt import solve
from lazyground.tasks.car_space import planning_space
from lazyground.tasks.outcome import Outcome, Step


def make_goal_source(world, regions):
    """The goal sampler registered for these regions' kind (:func:`lazyground.goals.goal_source_for`)."""
    return goal_source_for(tuple(regions), world)


def run(scene, grounding, settings, rng, worlds, *, seed: int | None = None, keep_tree: bool = False) -> Outcome:
    """Plan to whichever of ``grounding``'s goal regions is reachable first.

    Args:
        scene: the Scene.
        grounding: the request's Grounding (its ``goal_regions``).
        settings: PlannerSettings.
        rng: the only source of randomness.
        worlds: a :class:`~lazyground.tasks.worlds.Worlds` for ``scene``.
        seed: recorded in the result.
        keep_tree: keep the search tree (for viewers).

    Returns:
        An Outcome with one step; its path shortened and timed (lazyground.motion) when solved.
    """
    world = worlds.get()
    setup_s = worlds.setup_s
    source = make_goal_source(world, grounding.goal_regions)
    space = planning_space(scene, world.space, settings.kinematics)  # a car's curves, or world.space
    result = solve(space, world, source, world.start, settings, rng, seed=seed, keep_tree=keep_tree)
    # shortened and timed (issue #16); a car's path is shortened along its own curves (#17), then
    # timed as driven, resting at every gear change (a straight shortcut would leave the curves)
    cut = None
    if not space.linear_edges:
        result, cut = shorten_car_result(space, world, result, settings, rng)
    stops = None if space.linear_edges or not result.solved else space.cusp_indices(result.path)
    result, motion = motion_for_world(world, result, settings, rng, stops=stops, car=None if stops is None else space)
    motion = with_car_shortcut(motion, cut)
    notes = (motion.note,) if motion is not None and motion.note else ()
    return Outcome(result, (Step(grounding.action, result, setup_s, motion=motion),), world.space.names, notes)
