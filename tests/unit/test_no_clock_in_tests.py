"""No test decides its outcome on the real clock (issue 32; docs/reliability.md "No test decides on the real clock").

Every read of the machine's clock in tests/ is listed here with what it does; a new one fails this test until it
is reviewed and listed (a time limit as the deciding bound, an overshoot ratio in seconds, or a timeout accepted as
a pass are not allowed: drive by iteration caps and seeds, a ``FakeClock`` or ``work_clock``). The run-time half of
the rule is ``tests/conftest.py::no_outcome_on_the_real_clock`` (a stop condition's deadline firing on the real
clock fails the test), and ``real_clock`` marks are listed here too.
"""

from __future__ import annotations

import ast
from collections import Counter
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]
CLOCKS = {"time", "monotonic", "perf_counter", "process_time", "thread_time", "time_ns", "monotonic_ns",
          "perf_counter_ns", "process_time_ns", "now", "utcnow", "today"}
CLOCK_MODULES = {"time", "datetime"}

# file -> (reads of the clock, why none decides an outcome)
ALLOWED = {
    "conftest.py": (3, "the guard's list of real clocks (time.monotonic, perf_counter, time)"),
    "unit/toy.py": (2, "the toy checker's check_time statistic, never asserted against a bound"),
    "bench/test_bench_cli.py": (2, "a 300 s hang backstop while waiting for finished runs: errors on a hang only"),
}
REAL_CLOCK_MARKS = {
    "drake/test_cli.py": (1, "a Dubins plan under a 0.5 s limit: either exit code accepted, the output line checked"),
    "drake/test_families_reach.py": (1, "a 1 s bench run: wiring only, either outcome accepted"),
}


def _clock_reads(tree: ast.AST) -> int:
    """References to a clock function: ``time.perf_counter``, ``datetime.now``, or a name imported from time."""
    imported = {a.asname or a.name for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module in CLOCK_MODULES
                for a in n.names if a.name in CLOCKS}
    count = 0
    for n in ast.walk(tree):
        if isinstance(n, ast.Attribute) and n.attr in CLOCKS:
            base = n.value
            name = base.id if isinstance(base, ast.Name) else base.attr if isinstance(base, ast.Attribute) else ""
            count += name in CLOCK_MODULES
        elif isinstance(n, ast.Name) and n.id in imported and isinstance(n.ctx, ast.Load):
            count += 1
    return count


def _marks(tree: ast.AST) -> int:
    return sum(isinstance(n, ast.Attribute) and n.attr == "real_clock" for n in ast.walk(tree))


def _scan(what) -> Counter:
    out = Counter()
    for path in TESTS.rglob("*.py"):
        if path.name == Path(__file__).name:
            continue
        n = what(ast.parse(path.read_text(), str(path)))
        if n:
            out[path.relative_to(TESTS).as_posix()] = n
    return out


def test_every_read_of_the_real_clock_in_tests_is_reviewed():
    found = _scan(_clock_reads)
    assert found == {f: n for f, (n, _) in ALLOWED.items()}, (
        "a read of the machine's clock in tests/ changed: drive the test by iteration caps, seeds, a FakeClock or "
        f"work_clock, or list it in ALLOWED with why no outcome depends on it; found {dict(found)}")


def test_every_real_clock_mark_is_reviewed():
    found = _scan(_marks)
    assert found == {f: n for f, (n, _) in REAL_CLOCK_MARKS.items()}, found


def test_the_scan_sees_a_clock_read():
    src = "import time\nfrom time import perf_counter as pc\nt0 = time.monotonic()\nassert pc() - t0 < 1\n"
    assert _clock_reads(ast.parse(src)) == 2
    assert _clock_reads(ast.parse("import time\ntime.sleep(1)\n")) == 0
