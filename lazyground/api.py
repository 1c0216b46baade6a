"""The Python API: a scene and a text request in, a planned grounding out.

    from lazyground import api
    report = api.plan("parking_1", "park", seed=3)   # a bundled scene's name, or a path
    print(report.result.status, report.chosen_object)

Data flow: request → :func:`grounding.ground` → the task registered for its action
(:mod:`lazyground.tasks`: goal source → :func:`lazyground.planning.solve`, per step)
→ :class:`~lazyground.plan_report.PlanReport`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import grounding
from lazyground import tasks
from lazyground.plan_report import PlanReport
from lazyground.planning.stop import Clock, default_clock
from lazyground.scene import Scene, load_scene
from lazyground.settings import PlannerSettings, RunSettings
from lazyground.settings import coerce as coerce_setting
from lazyground.settings import from_scene as settings_from_scene
from lazyground.tasks.reach import make_goal_source  # noqa: F401  (a public name of the API)
from lazyground.tasks.worlds import Worlds


def run_settings(scene: Scene, **overrides) -> RunSettings:
    """The settings a run on ``scene`` uses (see :func:`lazyground.settings.from_scene`).

    Raises:
        ValueError: an unknown setting, or a value out of its range / choices.
    """
    return settings_from_scene(scene.planner, **overrides)


def planner_settings(scene: Scene, **overrides) -> PlannerSettings:
    """The planner's part of :func:`run_settings` (what :func:`lazyground.planning.solve` takes).

    Raises:
        ValueError: an unknown setting, or a value out of its range / choices.
    """
    return run_settings(scene, **overrides).planner


def plan(
    scene: Scene | str | Path,
    request: str,
    *,
    seed: int | None = None,
    keep_tree: bool = False,
    world=None,
    clock: Clock | None = None,
    **overrides,
) -> PlanReport:
    """Ground ``request`` in ``scene`` and plan to whichever interpretation is reachable.

    Args:
        scene: a Scene or a path to a scene file.
        request: the text request, e.g. "park" or "pick up a can".
        seed: the random seed (default: the scene's); recorded in the report.
        keep_tree: keep the search tree in the result (for visualisation).
        world: a prebuilt DrakeWorld for this scene (saves set-up time in loops); every task uses it.
        clock: the clock the time limit is read on and the time split measured by (default
            :func:`lazyground.planning.stop.default_clock`; tests pass a ``FakeClock``).
        **overrides: settings by name (strategy, goal_bias, step_size, time_limit, speed, ik_restarts, ...),
            declared in :mod:`lazyground.settings` (RunSettings' groups).

    Returns:
        The PlanReport; ``report.outcome`` holds the task's typed steps.

    Raises:
        ValueError: an unknown setting, a value out of its range / choices, or a seed that is not
            an integer >= 0.
        SceneError: the scene file is invalid.
        GroundingError: the request does not ground in the scene.
    """
    read = clock or default_clock
    t_call = read()
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    seed = scene.planner.seed if seed is None else coerce_setting("seed", seed)
    settings = run_settings(scene, **overrides)
    t0 = read()
    g = grounding.ground(request, scene)
    grounding_s = read() - t0
    worlds = Worlds(scene, world)
    outcome = tasks.run(scene, g, settings, np.random.default_rng(seed), worlds, seed=seed, keep_tree=keep_tree,
                        clock=clock, spent=grounding_s)  # the time limit counts the grounding
    return PlanReport(request, scene.name, seed, settings, g, outcome.result, outcome.joint_names, grounding_s,
                      worlds.setup_s, outcome, total_s=read() - t_call - worlds.setup_s)
