"""Suite-wide fixtures: outcomes are driven by iteration counts and seeds, never by the clock.

IK goal sampling bounds each attempt by a time budget (``IKSettings.attempt_budget``)
as well as by restarts and solver iterations; under load (a shared CI machine) the
budget would cut attempts short and change which samples a seed yields. The suite
runs every IK goal source built without explicit settings with no time budget, so an
attempt is bounded by ``restarts`` x ``major_iterations`` alone.
"""

from __future__ import annotations

import importlib.util
import time
from dataclasses import replace

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


@pytest.fixture
def cpu_clock(monkeypatch):
    """Time limits counted in this process's CPU time, for the tests of time-limit adherence.

    Whether the planner stops within its limit is a property of the code (how long one
    iteration or one IK solve runs past the deadline), but on a shared machine the wall
    clock also counts the time other processes hold the cores. The stop conditions'
    default clock (:data:`lazyground.planning.stop.CLOCK`, which every deadline and the
    reported times are read on) reads CPU time instead while the test runs, so deadlines,
    reported times and overshoots are measured in work done. No module's ``time`` is patched.
    """
    from lazyground.planning import stop

    monkeypatch.setattr(stop, "CLOCK", time.process_time)
    return time.process_time


REAL_CLOCKS = (time.monotonic, time.perf_counter, time.time)


@pytest.fixture(autouse=True)
def no_outcome_on_the_real_clock(request, monkeypatch):
    """Fail a test in which a stop condition's deadline fired on the real clock (docs/reliability.md).

    A deadline that fires on the wall clock lets the machine's load decide what the test sees; tests bound
    plans by ``max_iterations`` (tests/counts.py), drive a ``FakeClock``, or measure CPU time (``cpu_clock``).
    A test that must see a real deadline fire (the CLI's time-limit message, a subprocess) says so with
    ``@pytest.mark.real_clock``. Active once ``lazyground.planning.stop`` exists; plans in child processes
    are not seen.
    """
    if importlib.util.find_spec("lazyground.planning.stop") is None or request.node.get_closest_marker("real_clock"):
        yield
        return
    from lazyground.planning import stop

    fired = []
    original = stop.StopCondition.timed_out

    def timed_out(self):
        out = original(self)
        if out and self.clock is stop.default_clock and stop.CLOCK in REAL_CLOCKS:
            fired.append(self.budget)
        return out

    monkeypatch.setattr(stop.StopCondition, "timed_out", timed_out)
    yield
    if fired:
        pytest.fail(f"a {fired[0]:g} s deadline fired on the real clock ({len(fired)} readings past it): bound the "
                    "run by max_iterations (tests/counts.py), drive a FakeClock, or mark the test real_clock", False)
