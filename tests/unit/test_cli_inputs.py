"""audit8: bad input to `lazyground demo` and to `api.plan` is one line (exit 2) or a ValueError, never an internal error."""

from __future__ import annotations

import re

import pytest

from lazyground import api
from tests.unit.test_cli_outputs import refused
from tests.unit.test_grounding import REPO


@pytest.mark.parametrize("argv,message", [
    # before: "internal error: ValueError: expected non-negative integer", "internal error: FileExistsError: ...",
    # "internal error: FileNotFoundError: ..." (exit 3; the first after Drake had been imported)
    (["--seed", "-1"], "error: --seed must be >= 0, got -1"),
    (["--out", "{tmp}/file"], "error: --out {tmp}/file: is a file, not a folder"),
    (["--out", "/proc/lazyground_demo"], "error: --out /proc/lazyground_demo: cannot write there: "),
])
def test_demo_refuses_bad_options_before_planning(argv, message, tmp_path, capsys):
    (tmp_path / "file").write_text("")
    out = ["--out", "{tmp}/out"] if "--out" not in argv else []
    assert refused(["demo", *out, *argv], message, tmp_path, capsys) == ""


@pytest.mark.parametrize("seed,message", [
    (-1, "seed: must be >= 0, got -1"),  # before: numpy's "expected non-negative integer"
    (1.5, "seed: expected an integer, got 1.5"),  # before: planned silently with seed 1
    ("3", "seed: expected a number, got '3'"),  # before: planned with int("3")
])
def test_api_plan_checks_the_seed_before_planning(seed, message):
    with pytest.raises(ValueError, match=f"^{re.escape(message)}$"):
        api.plan("parking_1", "park", seed=seed)


def test_an_edge_resolution_too_fine_for_the_step_is_refused_before_planning(tmp_path, capsys):
    # audit8: planner: {edge_resolution: 1e-9} on parking_1 (step 2) asked for 2e10 configurations per edge: the
    # process grew until the kernel killed it (exit 137, nothing printed)
    from lazyground.settings import PlannerSettings

    with pytest.raises(ValueError, match=r"^edge_resolution: 1e-09 is too fine for step_size 2: the re-check of one edge "
                                         r"would test 2e\+10 configurations \(at most 100,000\); give edge_resolution >= 0\.0002$"):
        PlannerSettings(step_size=2.0, edge_resolution=1e-9)
    PlannerSettings(step_size=2.0, edge_resolution=2e-4)  # the finest allowed
    scene = tmp_path / "lot.yaml"
    scene.write_text(REPO.joinpath("yaml_scenes/parking_1.yaml").read_text().replace("edge_resolution: 0.1", "edge_resolution: 1.0e-9"))
    refused(["plan", str(scene), "park"], f"error: {scene}: edge_resolution: 1e-09 is too fine for step_size 2", tmp_path, capsys)


@pytest.mark.parametrize("argv,flag", [
    (["plan", "parking_1", "park", "--trajectory", "{tmp}/a.csv", "--trajectory", "{tmp}/b.csv"], "--trajectory"),
    (["plan", "parking_1", "park", "--seed", "1", "--seed=2"], "--seed"),
    (["plan", "parking_1", "park", "--time-limit", "1", "--time-limit", "2"], "--time-limit"),
])
def test_a_value_option_given_twice_is_refused(argv, flag, tmp_path, capsys):
    # issue 34: a repeated --trajectory silently took the last one
    assert refused(argv, f"error: argument {flag}: given twice; give it once", tmp_path, capsys) == ""
    assert not list(tmp_path.iterdir())


def test_version(capsys):
    # issue 34: there was no --version
    from lazyground import __version__
    from lazyground.cli import main

    assert main(["--version"]) == 0
    assert capsys.readouterr().out == f"lazyground {__version__}\n"
