"""Tasks: one registry keyed by the grounding's action, one signature.

    outcome = tasks.run(scene, grounding, settings, rng, worlds, seed=seed)

Every task is ``run(scene, grounding, settings, rng, worlds, *, seed, keep_tree, clock, spent) -> Outcome``
(:mod:`lazyground.tasks.outcome`). Entries name their module, imported on first use, so
importing this package does not import pydrake. A new task is one module plus one line here.
"""

from __future__ import annotations

import importlib

from lazyground.tasks.outcome import Grasp, Lift, ObjectStep, Outcome, Placement, Step
from lazyground.tasks.worlds import Worlds

TASKS: dict[str, str] = {
    "park": "lazyground.tasks.reach",
    "pick": "lazyground.tasks.reach",
    "place": "lazyground.tasks.place",  # pick and place, with fallback to another object
    "several": "lazyground.tasks.several",  # pick and place of several objects in turn (grounding.groups; #30)
}

__all__ = ["TASKS", "Grasp", "Lift", "ObjectStep", "Outcome", "Placement", "Step", "Worlds", "run", "task"]


def task(action: str):
    """The ``run`` function registered for ``action``.

    Raises:
        ValueError: no task is registered for ``action``.
    """
    module = TASKS.get(action)
    if module is None:
        raise ValueError(f"no task for action {action!r} (known: {', '.join(TASKS)})")
    return importlib.import_module(module).run


def run(scene, grounding, settings, rng, worlds: Worlds, *, seed: int | None = None, keep_tree: bool = False,
        clock=None, spent: float = 0.0) -> Outcome:
    """Run the task registered for ``grounding.action`` (see the module docstring); ``clock`` (default
    :func:`lazyground.planning.stop.default_clock`) is the one its stop conditions read; ``spent``: seconds of
    the time limit already used on it (grounding the request), taken off the task's deadline."""
    key = "several" if getattr(grounding, "groups", ()) else grounding.action
    return task(key)(scene, grounding, settings, rng, worlds, seed=seed, keep_tree=keep_tree, clock=clock,
                     spent=spent)
