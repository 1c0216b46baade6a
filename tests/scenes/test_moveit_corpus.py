"""MoveIt corpus regression (#15): every scene of tests/data/moveit_corpus and the paper's four
reference scenes (from ../shared; skipped when absent) imports and plans its natural request
with default settings. Success is a rate over seeds per scene and over the corpus (iteration
budget, not the clock), and every returned path is re-checked at a tenth of the planner's edge
resolution. Each test stands alone: runs are computed on first use and shared within the module.
"""

import pytest

pytest.importorskip("pydrake")

from lazyground.bench.moveit_corpus import corpus_entries, run_entry  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402

SEEDS = range(3)
MAX_ITERATIONS = 20_000  # the budget decides; the time limit is only a guard against a hung run
GUARD_S = 600.0
SCENE_RATE = 2 / 3  # per scene: at least 2 of the 3 seeds solve
CORPUS_RATE = 0.9
ENTRIES = corpus_entries()


@pytest.fixture(scope="module")
def runs_of(tmp_path_factory):
    """entry -> (runs, world), planned once per module whichever test asks first."""
    cache = {}

    def get(entry):
        if entry.name not in cache:
            cache[entry.name] = run_entry(entry, tmp_path_factory.mktemp("corpus"), SEEDS, max_iterations=MAX_ITERATIONS,
                                          time_limit=GUARD_S)
        return cache[entry.name]

    return get


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e.name)
def test_corpus_scene_plans_with_default_settings(entry, runs_of):
    runs, world = runs_of(entry)
    fine = world.scene.planner.edge_resolution / 10
    for run in runs:
        if run.status == "solved":
            assert path_is_valid(world.space, world, run.path, fine) == -1, f"seed {run.seed}: path collides at {fine:g}"
    assert [r.seed for r in runs] == list(SEEDS)
    solved = sum(r.status == "solved" for r in runs)
    assert solved / len(runs) >= SCENE_RATE, f"{entry.name}: {solved}/{len(runs)} solved: {[r.status for r in runs]}"


def test_corpus_success_rate_over_all_scenes(runs_of):
    statuses = [r.status for e in ENTRIES for r in runs_of(e)[0]]
    assert len(statuses) == len(ENTRIES) * len(SEEDS)
    solved = statuses.count("solved")
    assert solved / len(statuses) >= CORPUS_RATE, f"{solved}/{len(statuses)} solved"
