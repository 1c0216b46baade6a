"""Suite-wide fixtures: outcomes are driven by iteration counts and seeds, never by the clock.

IK goal sampling bounds each attempt by a time budget (``IKSettings.attempt_budget``)
as well as by restarts and solver iterations; under load (a shared CI machine) the
budget would cut attempts short and change which samples a seed yields. The suite
runs every IK goal source built without explicit settings with no time budget, so an
attempt is bounded by ``restarts`` x ``major_iterations`` alone.
"""

from __future__ import annotations

import importlib.util
import sys
import time
from dataclasses import replace
from types import SimpleNamespace

import pytest


def bound_ik_by_counts(patch: pytest.MonkeyPatch | None = None) -> None:
    """Make IK goal sources built without settings use no time budget (idempotent).

    Args:
        patch: records the change so it can be undone; None sets it for the process
            (worker processes of a test).
    """
    from lazyground.drake.ik import settings as ik_settings

    bound = replace(ik_settings.DEFAULT_IK_SETTINGS, attempt_budget=None)
    if patch is None:
        ik_settings.DEFAULT_IK_SETTINGS = bound
    else:
        patch.setattr(ik_settings, "DEFAULT_IK_SETTINGS", bound)


@pytest.fixture(autouse=True, scope="session")
def iteration_bound_ik():
    """IK attempts bounded by counts only (see the module docstring); a no-op without pydrake."""
    if importlib.util.find_spec("pydrake") is None:
        yield
        return
    patch = pytest.MonkeyPatch()
    bound_ik_by_counts(patch)
    yield
    patch.undo()


CPU_CLOCK = SimpleNamespace(perf_counter=time.process_time, monotonic=time.process_time, time=time.time, sleep=time.sleep)
"""A stand-in for the ``time`` module whose clock is this process's CPU time."""


@pytest.fixture
def cpu_clock(monkeypatch):
    """Time limits counted in this process's CPU time, for the tests of time-limit adherence.

    Whether the planner stops within its limit is a property of the code (how long one
    iteration or one IK solve runs past the deadline), but on a shared machine the wall
    clock also counts the time other processes hold the cores. Every ``lazyground``
    module that reads ``time.perf_counter`` reads CPU time instead while the test runs,
    so deadlines, reported times and overshoots are measured in work done. Modules are
    found by what they import, not by name, so the fixture survives refactoring.
    """
    import lazyground.api  # noqa: F401  (the planning stack: imported, so its modules are found below)
    import lazyground.goals  # noqa: F401
    import lazyground.planning.search  # noqa: F401

    if importlib.util.find_spec("pydrake") is not None:
        import lazyground.drake.ik  # noqa: F401
        import lazyground.tasks.place  # noqa: F401
    patched = [name for name, module in list(sys.modules.items())
               if name.split(".")[0] in ("lazyground", "grounding") and getattr(module, "time", None) is time]
    for name in patched:
        monkeypatch.setattr(sys.modules[name], "time", CPU_CLOCK)
    assert "lazyground.planning.search" in patched  # the planner's deadline at least
    return CPU_CLOCK
