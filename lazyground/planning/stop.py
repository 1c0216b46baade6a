"""One stop condition for every step of a run: a deadline, an iteration cap, an interrupt.

As OMPL's ``PlannerTerminationCondition``: search, goal sources, IK and motion take a
:class:`StopCondition` and ask it whether to stop; none of them reads the clock to
decide. The clock is injected (``time.monotonic`` by default), so a test drives time
with a :class:`FakeClock` instead of patching modules, and a task hands a share of its
budget to each step (:meth:`StopCondition.share`) instead of doing deadline arithmetic.

    stop = StopCondition.after(30.0, max_iterations=5000)
    pick = solve(..., stop=stop)                          # the whole remaining budget
    place = solve(..., stop=stop.share(0.4))              # at most 40 % of the 30 s, within what is left
"""

from __future__ import annotations

import enum
import math
import time
from dataclasses import dataclass, field
from typing import Callable

Clock = Callable[[], float]


class StopReason(str, enum.Enum):
    TIMEOUT = "timeout"
    ITERATIONS = "iterations"
    INTERRUPTED = "interrupted"

    def __str__(self) -> str:
        return self.value


CLOCK: Clock = time.monotonic
"""The clock behind :func:`default_clock`; the tests of time-limit adherence set it to CPU time (tests/conftest.py)."""


def default_clock() -> float:
    """The clock a StopCondition reads unless given one: :data:`CLOCK` (``time.monotonic``)."""
    return CLOCK()


@dataclass(frozen=True, eq=False)
class StopCondition:
    """When a run (or one step of it) must stop.

    Attributes:
        deadline: the clock reading at which time is up (None: never).
        max_iterations: stop once this many iterations are done (None: no cap).
        interrupt: a callable that returns True once the run must stop (e.g. a flag set by a signal).
        clock: the clock the deadline is read on; timers that only measure time may read it too.
        budget: the seconds the condition was given (for messages; inf without a deadline).
        start: the clock reading when the condition was made (:meth:`elapsed` counts from it).
    """

    deadline: float | None = None
    max_iterations: int | None = None
    interrupt: Callable[[], bool] | None = None
    clock: Clock = default_clock
    budget: float = math.inf
    start: float = field(default=None)  # type: ignore[assignment]  (set from the clock when None)
    _reason: list = field(default_factory=list, repr=False)  # the first reason a should_stop() answered True for

    def __post_init__(self):
        if self.start is None:
            object.__setattr__(self, "start", self.clock())
        if self.deadline is not None and self.budget == math.inf:
            object.__setattr__(self, "budget", self.deadline - self.start)

    @classmethod
    def after(cls, seconds: float | None, *, max_iterations: int | None = None,
              interrupt: Callable[[], bool] | None = None, clock: Clock | None = None,
              spent: float = 0.0) -> "StopCondition":
        """A condition whose deadline is ``seconds`` from now on ``clock`` (None: no deadline), less ``spent``
        seconds the run already used on it (grounding the request: the time limit counts it)."""
        clock = clock or default_clock
        now = clock()
        deadline = None if seconds is None or seconds == math.inf else now + seconds - spent
        return cls(deadline, max_iterations, interrupt, clock, math.inf if seconds is None else seconds, now)

    def now(self) -> float:
        """The clock's reading (for timers that measure a time split)."""
        return self.clock()

    def elapsed(self) -> float:
        """Seconds since the condition was made."""
        return self.clock() - self.start

    def remaining(self) -> float:
        """Seconds left before the deadline (inf without one; negative once past it)."""
        return math.inf if self.deadline is None else self.deadline - self.clock()

    def interrupted(self) -> bool:
        return self.interrupt is not None and bool(self.interrupt())

    def timed_out(self) -> bool:
        """Whether the deadline has passed (one clock reading)."""
        return self.deadline is not None and self.clock() >= self.deadline

    def should_stop(self, iterations: int = 0) -> bool:
        """Whether to stop now, ``iterations`` being done: interrupted, past the deadline or at the cap.

        The deadline is read first, then the cap, as a planner's loop asks (one clock reading per call).
        """
        # (interrupted() and timed_out() written out: the planner's loop asks this once or twice an iteration, #31)
        interrupt, deadline, cap = self.interrupt, self.deadline, self.max_iterations
        if interrupt is not None and interrupt():
            reason = StopReason.INTERRUPTED
        elif deadline is not None and self.clock() >= deadline:
            reason = StopReason.TIMEOUT
        elif cap is not None and iterations >= cap:
            reason = StopReason.ITERATIONS
        else:
            return False
        if not self._reason:
            self._reason.append(reason)
        return True

    @property
    def reason(self) -> StopReason | None:
        """Why :meth:`should_stop` first answered True (None while it has not)."""
        return self._reason[0] if self._reason else None

    def share(self, fraction: float | None = None, *, seconds: float | None = None,
              max_iterations: int | None = None) -> "StopCondition":
        """A child condition for one step: at most ``fraction`` of this budget, or ``seconds``, from now,
        and never past this deadline; the same clock and interrupt.

        Args:
            fraction: of this condition's budget (its seconds as given, not what is left).
            seconds: an absolute cap instead (None with ``fraction`` None: the whole remainder).
            max_iterations: the child's own cap (default: this one's; iterations count per step).

        Raises:
            ValueError: both ``fraction`` and ``seconds`` given.
        """
        if fraction is not None and seconds is not None:
            raise ValueError("share: give a fraction or seconds, not both")
        now = self.clock()
        cap = fraction * self.budget if fraction is not None else seconds
        deadline = self.deadline
        if cap is not None and cap != math.inf:
            deadline = now + cap if deadline is None else min(deadline, now + cap)
        budget = math.inf if deadline is None else deadline - now
        return StopCondition(deadline, self.max_iterations if max_iterations is None else max_iterations,
                             self.interrupt, self.clock, budget, now)


def never() -> StopCondition:
    """A condition that never stops (steps bounded by their own counts)."""
    return StopCondition()


class FakeClock:
    """A clock for tests: reads ``now``; advances by ``tick`` per reading and by :meth:`advance`."""

    def __init__(self, start: float = 0.0, tick: float = 0.0):
        self.t, self.tick = float(start), float(tick)
        self.reads = 0

    def __call__(self) -> float:
        t = self.t
        self.t += self.tick
        self.reads += 1
        return t

    def advance(self, seconds: float) -> None:
        self.t += seconds
