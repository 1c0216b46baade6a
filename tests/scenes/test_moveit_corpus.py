"""MoveIt corpus regression (#15): every scene of tests/data/moveit_corpus and the paper's four
reference scenes (from ../shared; skipped when absent) imports and plans its natural request
with default settings. Success is a rate over seeds (iteration budget, not the clock), and
every returned path is re-checked at a tenth of the planner's edge resolution.
"""

import pytest

pytest.importorskip("pydrake")

from lazyground.bench.moveit_corpus import corpus_entries, run_entry  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402

SEEDS = range(3)
MAX_ITERATIONS = 20_000  # the budget decides; the time limit is only a guard against a hung run
GUARD_S = 600.0
RUNS = []


@pytest.mark.parametrize("entry", corpus_entries(), ids=lambda e: e.name)
def test_corpus_scene_plans_with_default_settings(entry, tmp_path):
    runs, world = run_entry(entry, tmp_path, SEEDS, max_iterations=MAX_ITERATIONS, time_limit=GUARD_S)
    RUNS.extend(runs)
    fine = world.scene.planner.edge_resolution / 10
    for run in runs:
        if run.status == "solved":
            assert path_is_valid(world.space, world, run.path, fine) == -1, f"seed {run.seed}: path collides at {fine:g}"
    assert any(r.status == "solved" for r in runs), f"{entry.name}: no seed solved: {[r.status for r in runs]}"


def test_corpus_success_rate_over_all_scenes():
    if not RUNS:
        pytest.skip("run together with test_corpus_scene_plans_with_default_settings")
    solved = sum(r.status == "solved" for r in RUNS)
    assert solved / len(RUNS) >= 0.9, f"{solved}/{len(RUNS)} solved"
