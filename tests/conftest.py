"""Suite-wide fixtures: outcomes are driven by iteration counts and seeds, never by the clock.

IK goal sampling bounds each attempt by a time budget (``IKSettings.attempt_budget``)
as well as by restarts and solver iterations; under load (a shared CI machine) the
budget would cut attempts short and change which samples a seed yields. The suite
runs every IK goal source built without explicit settings with no time budget, so an
attempt is bounded by ``restarts`` x ``major_iterations`` alone. Shortcutting likewise stops on
``shortcut_iterations`` alone: its default 1 s budget is out of reach unless a test sets one.
"""

from __future__ import annotations

import importlib.util
import time
from dataclasses import replace

import numpy as np
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


def bound_shortcut_by_counts(patch: pytest.MonkeyPatch | None = None) -> None:
    """Make shortcutting stop on its attempt count (``shortcut_iterations``) alone: the default clock budget
    (``MotionSettings.shortcut_time``, 1 s) becomes out of reach unless a test or scene sets one (idempotent).

    A loaded machine otherwise cut shortcutting short and the real-clock guard failed the test.

    Args:
        patch: records the change so it can be undone; None sets it for the process.
    """
    import inspect

    from lazyground.settings import MotionSettings

    names = [n for n, p in inspect.signature(MotionSettings.__init__).parameters.items() if p.default is not p.empty]
    defaults = list(MotionSettings.__init__.__defaults__)
    defaults[names.index("shortcut_time")] = 1e9
    if patch is None:
        MotionSettings.__init__.__defaults__ = tuple(defaults)
    else:
        patch.setattr(MotionSettings.__init__, "__defaults__", tuple(defaults))


@pytest.fixture(autouse=True, scope="session")
def iteration_bound_ik():
    """IK attempts and shortcutting bounded by counts only (see the module docstring); IK's a no-op without
    pydrake."""
    patch = pytest.MonkeyPatch()
    bound_shortcut_by_counts(patch)
    if importlib.util.find_spec("pydrake") is not None:
        bound_ik_by_counts(patch)
    yield
    patch.undo()


class WorkClock:
    """A clock that reads work done, not time: seconds of modelled work, never the machine's clock.

    Each collision check, IK target solved and reading of the clock adds a fixed cost, the CPU time of one such
    operation measured once on the 2-core machine (docs/reliability.md): a configuration 20 us (alone or in a
    batch: parking 17-20 us, Fetch 6-8 us), an edge 200 us (a parking iteration, about one edge, takes
    ~260 us), an IK target 100 us (a batch solve per target), a reading 10 us (so a loop that only polls its
    deadline still ends). A deadline on this clock fires after the same work on any machine under any load,
    so a time-limit test is a function of its seeds: how much work a planner does past its deadline.
    """

    CONFIG = 20e-6
    EDGE = 200e-6
    IK_TARGET = 100e-6
    READ = 10e-6

    def __init__(self):
        self.work = 0.0

    def __call__(self) -> float:
        self.work += self.READ
        return self.work


@pytest.fixture
def work_clock(monkeypatch) -> WorkClock:
    """Time limits counted in work done (:class:`WorkClock`), for the tests of time-limit adherence.

    Whether the planner stops within its limit is a property of the code (how much it does past the
    deadline before it stops); on the machine's clock (or CPU time) the load and the machine decide how far a
    run gets. The stop conditions' default clock (:data:`lazyground.planning.stop.CLOCK`, which every deadline
    and reported time is read on) reads the work clock while the test runs; every collision check and IK
    solve of any world counts on it.
    """
    from lazyground.drake.checker import DrakeChecker
    from lazyground.drake.ik import solvers
    from lazyground.planning import stop

    clock = WorkClock()

    def counted(cls, name, cost):
        method = getattr(cls, name)

        def wrapper(self, *args, **kwargs):
            clock.work += cost(*args)
            return method(self, *args, **kwargs)

        monkeypatch.setattr(cls, name, wrapper)

    one_config = lambda *args: clock.CONFIG  # noqa: E731
    counted(DrakeChecker, "config_free", one_config)
    counted(DrakeChecker, "config_unpadded_free", one_config)
    # one row goes on to config_free, which counts it
    counted(DrakeChecker, "configs_free", lambda qs: clock.CONFIG * len(qs) if len(qs := np.atleast_2d(qs)) > 1 else 0.0)
    counted(DrakeChecker, "edge_free", lambda *args: clock.EDGE)
    counted(DrakeChecker, "edge_fraction", lambda *args: clock.EDGE)
    for cls in (solvers.BatchSolver, solvers.ProgramSolver):
        counted(cls, "solve", lambda frame, targets, starts: clock.IK_TARGET * len(targets))
    monkeypatch.setattr(stop, "CLOCK", clock)
    return clock


REAL_CLOCKS = (time.monotonic, time.perf_counter, time.time)


@pytest.fixture(autouse=True)
def no_outcome_on_the_real_clock(request, monkeypatch):
    """Fail a test in which a stop condition's deadline fired on the real clock (docs/reliability.md).

    A deadline that fires on the wall clock lets the machine's load decide what the test sees; tests bound
    plans by ``max_iterations`` (tests/counts.py), drive a ``FakeClock``, or count work (``work_clock``).
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
