"""Each planner setting is declared once (lazyground/settings.py); every layer derives from it
and rejects a bad value with one line naming the setting and its allowed values."""

import ast
import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

from lazyground import api, settings
from lazyground.cli import main
from lazyground.planning.problem import PlannerSettings
from lazyground.planning.rrt import ALGORITHMS
from lazyground.planning.strategies import STRATEGIES
from lazyground.scene import SceneError, parse_scene
from lazyground.scene.schema import AlgorithmSpec, PlannerSpec
from lazyground.settings import (BY_NAME, Algorithm, GoalExtension, GoalSamplingSettings, IKSolver, Layer, MotionSettings,
                                 RunSettings, SceneKeys, Strategy, TaskSettings, declared)

ROOT = Path(__file__).resolve().parents[2]
PARKING = ROOT / "yaml_scenes/parking_1.yaml"
CAR = "robot: {model: car, start: {car_x: 3, car_y: 3, car_qz: 0}, limits: {car_x: [0, 40], car_y: [0, 40]}}\n"


def test_every_layer_has_exactly_the_declared_fields(monkeypatch):
    # the declared defaults, not the suite's count-bound shortcutting (tests/conftest.py bound_shortcut_by_counts)
    monkeypatch.setattr(MotionSettings.__init__, "__defaults__", tuple(f.default for f in dataclasses.fields(MotionSettings)))
    names = lambda cls: [f.name for f in dataclasses.fields(cls)]  # noqa: E731
    groups = [getattr(RunSettings(), f.name) for f in dataclasses.fields(RunSettings)]
    assert [type(g) for g in groups] == [PlannerSettings, GoalSamplingSettings, MotionSettings, TaskSettings]
    assert [n for g in groups for n in names(g)] == [s.name for s in declared(Layer.API)]
    assert names(PlannerSpec) == [s.name for s in declared(Layer.SCENE)] + ["per_algorithm"]
    assert names(AlgorithmSpec) == [s.name for s in declared(Layer.PER_ALGORITHM)]
    assert all(getattr(g, s.name) == s.default for g in groups for s in declared(Layer.API) if hasattr(g, s.name))
    assert all(getattr(PlannerSpec(), s.name) == s.default for s in declared(Layer.SCENE))
    # each setting is one dataclass field, declared with its doc and layers in the field's metadata
    fields = [f for kind in (PlannerSettings, SceneKeys, GoalSamplingSettings, MotionSettings, TaskSettings)
              for f in dataclasses.fields(kind)]
    assert [f.name for f in fields] == [s.name for s in settings.SETTINGS]
    assert all(f.metadata["setting"]["doc"] == BY_NAME[f.name].doc for f in fields)


def test_flat_names_go_to_their_group():
    run = RunSettings.of(step_size=1.0, speed=0.5, give_up_after=7, place_share=0.25, ik_solver="snopt")
    assert run.planner.step_size == 1.0 and run.motion.speed == 0.5 and run.goal_sampling.give_up_after == 7
    assert run.task.place_share == 0.25 and run.goal_sampling.ik_solver is IKSolver.SNOPT
    assert run.replace(speed=0.25, goal_bias=0.5).motion.speed == 0.25 and run.replace(goal_bias=0.5).planner.goal_bias == 0.5
    with pytest.raises(ValueError, match="unknown planner setting 'stepsize'"):
        RunSettings.of(stepsize=1.0)
    with pytest.raises(ValueError, match="place_share: must be in"):
        RunSettings.of(place_share=0.0)


def test_registries_are_keyed_by_the_enums():
    assert set(STRATEGIES) == set(Strategy) and all(type(k) is Strategy for k in STRATEGIES)
    assert set(ALGORITHMS) == set(Algorithm) and all(type(k) is Algorithm for k in ALGORITHMS)


def test_settings_hold_enum_members_and_compare_as_names():
    s = PlannerSettings(strategy="random", algorithm="bidirectional", goal_extension="connect", max_iterations=5)
    assert s.strategy is Strategy.RANDOM and s.algorithm is Algorithm.BIDIRECTIONAL
    assert s.goal_extension is GoalExtension.CONNECT and s.strategy == "random"
    assert type(s.max_iterations) is int and dataclasses.replace(s, goal_bias=1).goal_bias == 1.0


@pytest.mark.parametrize("name, value, message", [
    ("step_size", -1, "step_size: must be > 0, got -1"),
    ("goal_bias", 1.5, "goal_bias: must be in [0, 1], got 1.5"),
    ("algorithm", "foo", "algorithm: unknown algorithm 'foo' (known: rrt, bidirectional)"),
    ("strategy", "greedy", "strategy: unknown strategy 'greedy' (known: reward-penalty, consecutive, random, cover, cover-connect)"),
    ("goal_extension", "jump", "goal_extension: unknown goal extension 'jump' (known: partial, extend, connect)"),
    ("max_iterations", 2.5, "max_iterations: expected an integer, got 2.5"),
    ("time_limit", float("inf"), "time_limit: must be finite, got inf"),
    ("time_limit", True, "time_limit: expected a number, got True"),
])
def test_api_rejects_a_bad_setting_before_planning(name, value, message):
    with pytest.raises(ValueError) as info:
        api.plan(PARKING, "park", **{name: value})
    assert str(info.value) == message


def test_api_rejects_an_unknown_setting():
    with pytest.raises(ValueError, match="unknown planner setting 'stepsize'"):
        api.planner_settings(parse_scene("name: x\n" + CAR, "ok.yaml", ROOT), stepsize=1.0)


@pytest.mark.parametrize("planner, error", [
    ("{step_size: -1}", "bad.yaml: planner.step_size: must be > 0, got -1 (line 3)"),
    ("{algorithm: foo}", "bad.yaml: planner.algorithm: unknown algorithm 'foo' (known: rrt, bidirectional) (line 3)"),
    ("{per_algorithm: {rrt: {goal_extension: jump}}}",
     "bad.yaml: planner.per_algorithm.rrt.goal_extension: unknown goal extension 'jump' (known: partial, extend, connect) (line 3)"),
    ("{per_algorithm: {prm: {}}}", "bad.yaml: planner.per_algorithm.prm: unknown algorithm (known: rrt, bidirectional) (line 3)"),
])
def test_scene_file_rejects_a_bad_setting(planner, error):
    with pytest.raises(SceneError) as info:
        parse_scene(f"name: x\n{CAR}planner: {planner}\n", "bad.yaml", ROOT)
    assert str(info.value) == error


@pytest.mark.parametrize("flag, value, error", [
    ("--step-size", "-1", "error: --step-size must be > 0, got -1"),
    ("--goal-bias", "2", "error: --goal-bias must be in [0, 1], got 2"),
    ("--seed", "-3", "error: --seed must be >= 0, got -3"),
])
def test_cli_rejects_a_bad_flag_with_one_line(capsys, flag, value, error):
    assert main(["plan", str(PARKING), "park", flag, value]) == 2
    assert capsys.readouterr().err.strip().splitlines() == [error]


def test_bench_rejects_a_bad_sweep_value(capsys):
    assert main(["bench", "--scenes", "parking_1", "--biases", "0.05,1.5", "--runs", "1"]) == 2
    assert "--biases: must be in [0, 1], got 1.5" in capsys.readouterr().err


def test_cli_has_one_flag_per_cli_setting():
    from lazyground.cli import build_parser

    plan = build_parser()._subparsers._group_actions[0].choices["plan"]
    flags = {o for a in plan._actions for o in a.option_strings}
    assert {s.flag for s in declared(Layer.CLI)} <= flags


def test_docs_settings_table_is_the_generated_one():
    text = (ROOT / "docs/scene_format.md").read_text()
    assert settings.markdown_table() in text, "docs/scene_format.md: regenerate with python3 -m lazyground.cli_options"


def test_names_are_written_once():
    """No string literal in lazyground/, grounding/ or tools/ spells a strategy, algorithm or
    goal-extension name, except the enums' declarations in lazyground/settings.py."""
    names = {m.value for enum in (Strategy, Algorithm, GoalExtension) for m in enum}
    found = []
    for folder in ("lazyground", "grounding", "tools"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            if path == ROOT / "lazyground/settings.py":
                continue
            tree = ast.parse(path.read_text())
            docstrings = {id(n.body[0].value) for n in ast.walk(tree)
                          if isinstance(n, (ast.Module, ast.ClassDef, ast.FunctionDef)) and n.body
                          and isinstance(n.body[0], ast.Expr) and isinstance(n.body[0].value, ast.Constant)}
            found += [f"{path.relative_to(ROOT)}:{n.lineno}: {n.value!r}" for n in ast.walk(tree)
                      if isinstance(n, ast.Constant) and n.value in names and id(n) not in docstrings]
    assert found == []


def test_loading_a_scene_imports_neither_the_planner_nor_scipy_nor_pydrake():
    code = ("import sys; from lazyground.scene import load_scene; load_scene(sys.argv[1]); "
            "print(' '.join(m for m in ('pydrake', 'scipy', 'lazyground.planning.rrt', 'lazyground.planning.search') "
            "if m in sys.modules))")
    for scene in ("parking_1", "fetch_cans_1", "kitchen_put_cup_on_table"):
        out = subprocess.run([sys.executable, "-c", code, str(ROOT / f"yaml_scenes/{scene}.yaml")], cwd=ROOT,
                             capture_output=True, text=True, check=True, env={"PYTHONPATH": str(ROOT), "PATH": ""})
        assert out.stdout.strip() == "", f"{scene}: loading imported {out.stdout.strip()}"


def test_every_setting_has_a_doc_and_a_valid_default():
    for s in settings.SETTINGS:
        assert s.doc and s.layers
        assert s.problem(s.default) is None, s.name
    assert BY_NAME["edge_resolution"].optional and PlannerSettings().resolution == 0.05
