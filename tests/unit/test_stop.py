"""The one stop condition (lazyground.planning.stop), on a fake clock."""

import math

import pytest

from lazyground.planning.stop import FakeClock, StopCondition, StopReason


def test_deadline_on_a_fake_clock():
    clock = FakeClock(start=10.0)
    stop = StopCondition.after(2.0, clock=clock)
    assert stop.budget == 2.0 and stop.remaining() == 2.0 and not stop.should_stop() and stop.reason is None
    clock.advance(1.5)
    assert stop.elapsed() == 1.5 and not stop.should_stop()
    clock.advance(0.5)
    assert stop.should_stop() and stop.reason is StopReason.TIMEOUT and stop.remaining() == 0.0


def test_a_ticking_clock_stops_after_so_many_readings():
    stop = StopCondition.after(0.01, clock=FakeClock(tick=1e-3))  # the reading in after() is the first tick
    readings = 0
    while not stop.should_stop():
        readings += 1
    assert readings == 9 and stop.reason is StopReason.TIMEOUT


def test_iteration_cap_and_interrupt():
    stop = StopCondition(max_iterations=5, clock=FakeClock())
    assert not stop.should_stop(4) and stop.should_stop(5) and stop.reason is StopReason.ITERATIONS
    assert not stop.should_stop()  # no count given: the cap is the caller's (goal sampling asks this way)
    flag = []
    stop = StopCondition.after(None, interrupt=lambda: bool(flag), clock=FakeClock())
    assert not stop.should_stop() and stop.remaining() == math.inf
    flag.append(1)
    assert stop.should_stop() and stop.reason is StopReason.INTERRUPTED


def test_a_share_never_outlasts_its_parent():
    clock = FakeClock()
    parent = StopCondition.after(10.0, max_iterations=100, clock=clock)
    clock.advance(8.0)
    place = parent.share(0.4)  # 40 % of the 10 s, but only 2 s are left
    assert place.budget == 2.0 and place.max_iterations == 100
    clock.advance(-7.0)  # (a fake clock may go back: a share made earlier)
    early = parent.share(0.4)
    assert early.budget == 4.0 and early.deadline == 5.0
    assert parent.share(seconds=0.25).budget == 0.25 and parent.share().deadline == parent.deadline
    never = StopCondition(clock=clock)
    assert never.share().deadline is None and never.share(seconds=1.0).budget == 1.0
    flag = [1]
    child = StopCondition(interrupt=lambda: bool(flag), clock=clock).share(seconds=5.0)
    assert child.should_stop() and child.reason is StopReason.INTERRUPTED  # the parent's interrupt reaches it
    with pytest.raises(ValueError):
        parent.share(0.5, seconds=1.0)


def test_a_zero_budget_is_spent_at_once():
    stop = StopCondition(clock=FakeClock()).share(seconds=0.0)
    assert stop.should_stop()
