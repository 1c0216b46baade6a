"""``lazyground check-robot``: a clean robot, a missing mesh, a self-colliding named pose, an unknown package."""

import pytest

pytest.importorskip("pydrake")

from lazyground.cli import main  # noqa: E402

from tests.drake.ros_package import PACKAGE, make_package  # noqa: E402


@pytest.fixture(autouse=True)
def _isolated(tmp_path, monkeypatch):
    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)


def _run(capsys, *argv):
    code = main(["check-robot", *argv])
    out = capsys.readouterr()
    return code, out.out.strip().splitlines(), out.err.strip()


@pytest.mark.parametrize("robot,dof", [("panda", 7), ("ur5e", 6), ("fetch", 8)])
def test_bundled_robots_are_clean(capsys, robot, dof):
    code, lines, err = _run(capsys, robot)
    assert code == 0 and not err
    assert f"DOF: {dof}" in lines and lines[-1].startswith(f"ok: {robot}.urdf loads with {dof} DOF")
    assert any(line.strip().endswith(": free") for line in lines)  # its named poses were checked
    assert any("limits [" in line and "velocity" in line for line in lines)


def test_unbounded_positions_get_a_note_naming_them(capsys):
    # planning refuses a position without limits unless the scene gives robot.limits; check-robot said only "ok"
    code, lines, _ = _run(capsys, "car")
    notes = [line for line in lines if line.startswith("note: unbounded positions")]
    assert code == 0 and lines[-1].startswith("ok: car.urdf")
    assert len(notes) == 1 and "car_x, car_y " in notes[0] and "car_qz" not in notes[0]  # the heading wraps
    _, lines, _ = _run(capsys, "fetch")  # continuous joints wrap: no note
    assert not any("unbounded" in line for line in lines)


def test_a_clean_robot_prints_nothing_on_stderr():
    # audit8: every check-robot run printed "INFO:drake:Allocating contexts to support implicit context parallelism 2"
    import subprocess
    import sys
    from pathlib import Path

    run = subprocess.run([sys.executable, "-m", "lazyground", "check-robot", "panda"], capture_output=True, text=True,
                         cwd=Path(__file__).resolve().parents[2])
    assert run.returncode == 0 and run.stderr == ""


def test_ros_package_with_srdf_reports_meshes_pairs_and_unsupported(tmp_path, capsys):
    pkg = make_package(tmp_path)
    code, lines, _ = _run(capsys, str(pkg / "urdf" / "my_arm.urdf"), "--srdf", str(pkg / "config" / "my_arm.srdf"))
    text = "\n".join(lines)
    assert "meshes: 25 converted to OBJ" in text and f"package {PACKAGE}: {pkg}" in text
    assert "  fts_robotside: 1 mesh" in text and "  ready: free" in text
    assert "3 disabled pairs applied" in text and "skipped: 1 (e.g. robotiq_inner_knuckle-fts_robotside)" in text
    assert "unsupported: SRDF <group> x1 read but not used" in text
    # the SRDF's "folded" state folds the wrist onto the upper arm: exit 2, the verdict names it
    assert code == 2 and lines[-1].startswith("1 problem(s): named pose 'folded' self-collides: ")
    assert "upper_arm_link-wrist_1_link" in lines[-1]


def test_missing_mesh_is_one_line_naming_the_file(tmp_path, capsys):
    pkg = make_package(tmp_path)
    (pkg / "meshes" / "fts.stl").unlink()
    code, lines, err = _run(capsys, str(pkg / "urdf" / "my_arm.urdf"))
    assert code == 2 and not lines and "\n" not in err
    assert "mesh 'package://my_arm_description/meshes/fts.stl'" in err and f"{pkg / 'meshes' / 'fts.stl'} not found" in err


def test_unknown_package_names_it_and_the_fix(tmp_path, capsys):
    pkg = make_package(tmp_path, mesh_uri="package://arm_meshes/meshes")
    code, _, err = _run(capsys, str(pkg / "urdf" / "my_arm.urdf"))
    assert code == 2 and "\n" not in err
    assert f"unknown package 'arm_meshes' (known: {PACKAGE})" in err and "--package arm_meshes=DIR" in err
    code, lines, _ = _run(capsys, str(pkg / "urdf" / "my_arm.urdf"), "--package", f"arm_meshes={pkg}")
    assert "DOF: 6" in lines  # it loads; without its SRDF the sensor link overlaps wrist 2 in every pose (#28)
    assert code == 2 and lines[-1].startswith("1 problem(s): 1 link pair(s) touch in at least 95% of 200 sampled")
    assert "fts_robotside-wrist_2_link" in lines[-1]


def test_not_a_model_is_one_line(tmp_path, capsys):
    (tmp_path / "robot.txt").write_text("<robot/>")
    code, _, err = _run(capsys, str(tmp_path / "robot.txt"))
    assert code == 2 and "must be a .urdf, .sdf or .xacro file" in err and "\n" not in err.strip()
    (tmp_path / "robot.xacro").write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                          '<link name="$(arg ur_type)"/></robot>')
    code, _, err = _run(capsys, str(tmp_path / "robot.xacro"))
    assert code == 2 and "xacro argument 'ur_type' is required" in err and "--xacro-arg ur_type=VALUE" in err
    assert "\n" not in err.strip()
    code, _, err = _run(capsys, "no_such_robot")
    assert code == 2 and "no model file 'no_such_robot'" in err
