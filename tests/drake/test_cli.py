"""The `lazyground` command: JSON output, exit codes, one-line errors and statuses."""

import json
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

pytest.importorskip("pydrake")

from lazyground.cli import main  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
P1 = str(ROOT / "yaml_scenes/parking_1.yaml")
BY_SEED = ["--time-limit", "1000", "--shortcut-time", "1e9"]  # parking_1 solves every seed in a few hundred iterations: the seed decides, not the clock

LOT = textwrap.dedent(
    """\
    name: tiny_lot
    robot:
      model: car
      start: {{car_x: {x}, car_y: 3.0, car_qz: 0.0}}
      limits: {{car_x: [0, 30], car_y: [0, 20]}}
      weights: {{car_qz: 2.0}}
    obstacles:
      - {{id: pillar, geometry: {{cylinder: {{radius: 0.3, length: 3}}}}, pose: {{xyz: [10, 3, 1.5]}}}}
      {extra}
    objects:
      - {{id: spot_1, type: parking_spot, geometry: {{box: [5.5, 2.6, 0.05]}}, pose: {{xyz: [20, 17, 0], rpy: [0, 0, 1.5708]}}}}
      - {{id: spot_2, type: parking_spot, occupied: true, geometry: {{box: [5.5, 2.6, 0.05]}}, pose: {{xyz: [23, 17, 0], rpy: [0, 0, 1.5708]}}}}
    planner: {{step_size: 1.0, time_limit: 1000, max_iterations: 3000}}
    """
)  # outcomes bounded by iterations: the time limit is a backstop a loaded machine never reaches


def lot(tmp_path, x=3.0, extra=""):
    p = tmp_path / "lot.yaml"
    p.write_text(LOT.format(x=x, extra=extra))
    return str(p)


def test_plan_json_solves(capsys):
    assert main(["plan", P1, "park", "--json", "--seed", "1"] + BY_SEED) == 0
    doc = json.loads(capsys.readouterr().out)
    for key in ("status", "request", "interpretations", "chosen", "joint_names", "path", "time_s", "iterations",
                "tree_size", "goal_samples", "resamplings", "seed"):
        assert key in doc
    assert doc["status"] == "solved" and doc["seed"] == 1
    assert doc["joint_names"] == ["car_x", "car_y", "car_qz"]
    assert doc["chosen"]["interpretation"] == f"park:{doc['chosen']['object']}"
    assert {i["id"] for i in doc["interpretations"]} >= {doc["chosen"]["interpretation"]}
    assert all(len(q) == 3 for q in doc["path"])
    assert doc["time_s"] >= doc["time_split_s"]["goal_sampling"] + doc["time_split_s"]["collision_checking"]


@pytest.mark.real_clock  # a dubins plan under a 0.5 s limit: either outcome is accepted, the test checks the output line
def test_plan_kinematics(capsys):
    assert main(["plan", P1, "park", "--json", "--seed", "1"]) == 0  # the parking scenes drive Reeds-Shepp curves
    doc = json.loads(capsys.readouterr().out)
    assert doc["kinematics"] == "reeds-shepp" and isinstance(doc["cusps"], int)
    steps = [abs(b[0] - a[0]) + abs(b[1] - a[1]) for a, b in zip(doc["path"][:-1], doc["path"][1:])]
    assert max(steps) <= 0.1 * 2**0.5 + 1e-6  # dense samples along the curves
    assert main(["plan", P1, "park", "--json", "--seed", "1", "--kinematics", "holonomic"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["kinematics"] == "holonomic" and doc["cusps"] is None
    assert main(["plan", P1, "park", "--seed", "1", "--kinematics", "dubins", "--time-limit", "0.5"]) in (0, 1)
    assert "dubins" in capsys.readouterr().out.splitlines()[0]


def test_car_kinematics_need_a_car(capsys):
    fetch = str(ROOT / "yaml_scenes/fetch_cans_1.yaml")
    assert main(["plan", fetch, "pick up a can", "--kinematics", "reeds-shepp"]) == 2
    err = capsys.readouterr().err.strip()
    assert "kinematics" in err and len(err.splitlines()) == 1
    # audit8: the path read "models//.../models/fetch/fetch.urdf/robot.yaml" (the model's absolute path inside a template)
    assert err.endswith("/models/fetch/robot.yaml); this robot has none") and "//" not in err, err


def test_plan_bidirectional(capsys):
    assert main(["plan", P1, "park", "--json", "--seed", "1", "--algorithm", "bidirectional"] + BY_SEED) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "solved" and doc["algorithm"] == "bidirectional"
    assert doc["chosen"]["interpretation"] == f"park:{doc['chosen']['object']}"
    assert main(["plan", P1, "park", "--seed", "1", "--algorithm", "bidirectional"] + BY_SEED) == 0
    assert "reward-penalty, bidirectional" in capsys.readouterr().out


def test_plan_human_output(capsys):
    assert main(["plan", P1, "park", "--seed", "2"] + BY_SEED) == 0
    out = capsys.readouterr().out
    assert "reached: park:spot_" in out and "iterations" in out


def test_start_in_collision_names_the_pair(tmp_path, capsys):
    assert main(["plan", lot(tmp_path, x=10.0), "park", "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "invalid_start"
    assert "car_body collides with pillar" in doc["message"]


def test_no_valid_goal(tmp_path, capsys):
    blocker = "- {id: blocker, geometry: {box: [3, 6, 2]}, pose: {xyz: [20, 17, 1]}}"
    assert main(["plan", lot(tmp_path, extra=blocker), "park", "--json", "--no-reach-prior"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "no_valid_goal"
    assert "spot_1/forwards: 50 configurations tried, 0 valid (in collision x50)" in doc["message"]


def test_timeout_when_unreachable(tmp_path, capsys):
    wall = "- {id: wall, geometry: {box: [30, 0.3, 2]}, pose: {xyz: [15, 12, 1]}}"
    assert main(["plan", lot(tmp_path, extra=wall), "park", "--json", "--no-reach-prior"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "timeout" and doc["iterations"] == 3000  # the scene's max_iterations


@pytest.mark.parametrize("extra", ["- {id: wall, geometry: {box: [30, 0.3, 2]}, pose: {xyz: [15, 12, 1]}}",
                                   "- {id: blocker, geometry: {box: [3, 6, 2]}, pose: {xyz: [20, 17, 1]}}"])
def test_every_spot_proven_unreachable_ends_at_once(tmp_path, capsys, extra):
    """The reach prior (#33): a wall across the lot (or a box over the spot) leaves the car's disc no way to the
    spot, so the request ends before any iteration, no_valid_goal, exit 1, one line saying so."""
    assert main(["plan", lot(tmp_path, extra=extra), "park", "--json"]) == 1
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "no_valid_goal" and doc["iterations"] == 0 and doc["goal_samples"] == 0
    assert doc["message"].startswith("no reachable goal: all 1 interpretation(s) proven unreachable by the reach prior")
    assert "\n" not in doc["message"]
    assert doc["proven_unreachable"] == {"interpretations": 1, "of": 1, "by": "reach prior"}
    assert doc["regions"]["spot_1/forwards"]["unreachable"] == "reach prior"
    assert main(["plan", lot(tmp_path, extra=extra), "park"]) == 1
    out = capsys.readouterr().out
    assert "note: 1 of 1 interpretations proven unreachable by the reach prior" in out
    assert "status: no_valid_goal: no reachable goal" in out


@pytest.mark.parametrize(
    "argv,fragment",
    [
        (["plan", "no/such.yaml", "park"], "no such scene file"),
        (["plan", P1, "fly to the moon"], "error: "),
        (["plan", P1, "park", "--goal-bias", "2"], "--goal-bias must be in [0, 1]"),
        (["plan", P1, "park", "--time-limit", "-1"], "--time-limit must be > 0"),
        (["plan", P1, "park", "--strategy", "greedy"], "invalid choice: 'greedy'"),
        (["plan", P1, "park", "--kinematics", "teleport"], "invalid choice: 'teleport'"),
        (["plan", P1], "the following arguments are required: request"),
        (["frobnicate"], "invalid choice: 'frobnicate'"),
    ],
)
def test_bad_input_exits_2_with_one_line(argv, fragment, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert fragment in err and len(err.splitlines()) == 1


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="needs /dev/full")
def test_a_full_disk_while_writing_an_output_is_bad_input(tmp_path, capsys):
    # audit8: "internal error: OSError: [Errno 28] No space left on device (rerun with --debug)", exit 3
    full = tmp_path / "t.csv"
    full.symlink_to("/dev/full")
    assert main(["plan", P1, "park", "--seed", "1", "--trajectory", str(full)] + BY_SEED) == 2
    out, err = capsys.readouterr()
    assert "reached: park:spot_" in out  # the plan itself is reported
    assert err.splitlines() == [f"error: --trajectory {full}: cannot write: No space left on device"]


def test_subprocess_error_has_no_traceback(tmp_path):
    bad = lot(tmp_path, x=999)
    run = subprocess.run([sys.executable, "-m", "lazyground", "plan", bad, "park"], capture_output=True, text=True)
    assert run.returncode == 2
    assert "Traceback" not in run.stderr
    assert run.stderr.strip().splitlines() == [f"error: {bad}: robot.start.car_x: 999 is outside the joint limits [0, 30]"]
    debug = subprocess.run([sys.executable, "-m", "lazyground", "--debug", "plan", bad, "park"], capture_output=True, text=True)
    assert debug.returncode == 2 and "Traceback" in debug.stderr


def test_ground_json(capsys):
    assert main(["ground", P1, "park", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["ambiguous"] is True and doc["action"] == "park"
    assert {i["id"] for i in doc["interpretations"]} == {"park:spot_b1", "park:spot_b9", "park:spot_t3", "park:spot_t10"}
    assert all(len(i["goal_regions"]) == 2 for i in doc["interpretations"])


def test_reader_closing_the_pipe_is_silent():
    """`lazyground plan ... --json | head`: the reader has gone before the report is written."""
    proc = subprocess.Popen([sys.executable, "-m", "lazyground", "plan", P1, "park", "--json", "--seed", "0", *BY_SEED],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=ROOT)
    proc.stdout.close()  # before the child writes anything: its first write meets a closed pipe
    err = proc.stderr.read().decode()
    assert proc.wait() == 141
    assert err == ""
