"""Ctrl-C during a plan: status ``interrupted`` with partial statistics, CLI exit 130, one line.

(``lazyground bench``'s Ctrl-C — finished runs kept, exit 130 — is tested in
tests/bench/test_bench_cli.py::test_ctrl_c_keeps_finished_runs.)
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
import time

import numpy as np

from lazyground.planning import PlannerSettings, PlanStatus, solve
from tests.reliability.conftest import REPO, needs_drake, walled_lot
from tests.unit.toy import SPACE, START, UNREACHABLE, WALLS, BoxWorld, goal_source


class InterruptingWorld(BoxWorld):
    """The toy world, pressing Ctrl-C after ``after`` collision checks."""

    def __init__(self, boxes, after: int):
        super().__init__(boxes)
        self.after = after

    def configs_free(self, qs):
        if self.checks >= self.after:
            raise KeyboardInterrupt
        return super().configs_free(qs)


def test_solve_returns_interrupted_with_partial_statistics():
    world = InterruptingWorld(WALLS, after=3000)
    settings = PlannerSettings(step_size=0.5, time_limit=1e6, goal_bias=0.1)  # the interrupt, not the clock, ends it
    res = solve(SPACE, world, goal_source(world, [UNREACHABLE]), START, settings, np.random.default_rng(0), seed=0)
    assert res.status is PlanStatus.INTERRUPTED and res.path is None
    assert res.message == "stopped by Ctrl-C"  # issue 34: the report said "status: interrupted: interrupted"
    assert res.iterations > 10 and res.tree_size > 10 and res.goal_samples
    assert res.time_s > 0 and res.seed == 0
    assert res.region_stats[0].valid > 0


def with_ctrl_c() -> None:
    """Give the child the default Ctrl-C: a shell running the tests in the background
    (``pytest &``) hands its children SIGINT ignored, and Python keeps it ignored."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _popen(argv):
    return subprocess.Popen(argv, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=with_ctrl_c)


def _interrupt(proc, after: float, backstop: float = 120.0):
    """Ctrl-C ``after`` s into the plan; the answer (out, err). ``backstop`` only ends a hung child (the test then
    errors with TimeoutExpired): no outcome is decided by how long the child took."""
    time.sleep(after)
    assert proc.poll() is None, proc.communicate()
    proc.send_signal(signal.SIGINT)
    try:
        out, err = proc.communicate(timeout=backstop)
    finally:
        if proc.poll() is None:
            proc.kill()
    return out, err


READY = (
    "import sys\n"
    "import lazyground.api, lazyground.drake.world, lazyground.report\n"
    "from lazyground.cli import main\n"
    "from lazyground.planning import search\n"
    "left = search.Search.time_left\n"
    "def announce(self):\n"
    "    if self.iterations >= 20 and not getattr(self, 'announced', False):\n"
    "        self.announced = True\n"
    "        print('planning', file=sys.stderr, flush=True)\n"
    "    return left(self)\n"
    "search.Search.time_left = announce\n"
    "sys.exit(main(sys.argv[1:]))\n"
)
"""Runs the CLI like ``python -m lazyground``, and says on stderr once the planner has done 20 iterations, so the
signal lands inside the planner, after some work, however long imports, world building and the iterations take
on a loaded machine (no outcome waits on the clock)."""


def _popen_planning(argv):
    """The CLI with ``argv``, once its planner has done 20 iterations (the "planning" line read off stderr)."""
    proc = _popen([sys.executable, "-c", READY] + argv)
    assert proc.stderr.readline().strip() == "planning", proc.communicate()
    return proc


@needs_drake
def test_cli_ctrl_c_exits_130_with_one_line(tmp_path):
    scene = walled_lot(tmp_path)
    proc = _popen_planning(["plan", str(scene), "park", "--time-limit", "1000"])  # the walled lot: never solved
    out, err = _interrupt(proc, after=0.1)
    assert proc.returncode == 130, (out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted"), err
    assert "Traceback" not in err


@needs_drake
def test_cli_ctrl_c_during_planning_prints_partial_statistics(tmp_path):
    """The signal lands inside the planner (a line on stderr says it started), which reports what it did."""
    scene = walled_lot(tmp_path)
    proc = _popen_planning(["plan", str(scene), "park", "--time-limit", "1000", "--json"])
    out, err = _interrupt(proc, after=0.1)
    assert proc.returncode == 130, (out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("interrupted after "), err
    doc = json.loads(out)
    assert doc["status"] == "interrupted" and doc["path"] is None
    assert doc["iterations"] > 0 and doc["tree_size"] > 1 and doc["goal_samples"] > 0
    assert doc["iterations"] >= 20  # the signal came after the announced iterations
    assert doc["time_s"] > 0  # status 'interrupted', not 'timeout': stopped by the signal, before the 1000 s limit
