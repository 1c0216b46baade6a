"""sscbirrt's CBiRRT as a bench peer: our checker, our goal samples, its path re-checked as ours are."""

from __future__ import annotations

import numpy as np
import pytest

from lazyground.bench import arms
from lazyground.bench.runner import SSCBIRRT, RunSpec, load_problem, run
from lazyground.planning import path_is_valid

pytest.importorskip("sscbirrt", reason="sscbirrt peer skipped: the 'sscbirrt' package is not installed (pip install .[bench])")


def test_cbirrt_on_a_small_arm_shares_goal_samples_and_checker():
    from lazyground.bench.sscbirrt_peer import plan

    key = arms.arm_key(8)
    problem = load_problem(key)
    world = problem.world
    # a generous limit: the seeded search ends by solving, not by the clock
    spec = RunSpec(key, SSCBIRRT, "goal-states", None, 0, 120.0)
    checks0 = world.checks
    out, path = plan(problem, spec)
    assert out["status"] == "solved", out["message"]
    assert out["goal_samples"] == 10 and out["iterations"] > 0 and out["tree_size"] > 2
    assert 0 < out["collision_checks"] <= world.checks - checks0  # our checker did the checks
    assert np.allclose(path[0], world.start)
    ends = [r.contains(path[-1]) for r in problem.regions]
    assert any(ends) and out["region"] == problem.regions[ends.index(True)].id
    assert path_is_valid(world.space, world, path, arms.EDGE_RESOLUTION / 20) == -1  # finer than the peer's re-check
    assert out["time_s"] >= out["goal_sampling_s"] + out["collision_s"]


def test_the_runner_row_names_the_peer():
    row = run(RunSpec(arms.arm_key(8), SSCBIRRT, "goal-states", None, 1, 120.0))
    assert row["planner"] == SSCBIRRT and row["status"] == "solved", row["message"]
    assert row["bias"] == "" and int(row["collision_checks"]) > 0
