"""Issue #18, done when: a robot description laid out as ROS packages are (URDF with package://
STL collision meshes, an SRDF with disabled pairs and named states, a z-forward tool frame) plans
"pick up a cup" with no edit to the robot's files, only a scene that points at them."""

import hashlib
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.cli import main  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402
from lazyground.robots.description import prepare_model  # noqa: E402
from lazyground.scene import SceneError, load_scene  # noqa: E402

from tests.counts import BY_COUNTS  # noqa: E402
from tests.drake.ros_package import PACKAGE, make_package, scene_text  # noqa: E402


ROS_READY = np.array([0, -1.5708, 1.5708, -1.5708, -1.5708, 0])  # the SRDF's "ready"


def _digest(folder: Path) -> str:
    h = hashlib.sha256()
    for path in sorted(folder.rglob("*")):
        if path.is_file():
            h.update(path.name.encode() + path.read_bytes())
    return h.hexdigest()


@pytest.fixture()
def workspace(tmp_path, monkeypatch):
    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "cache"))  # converted meshes go here
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    pkg = make_package(tmp_path)
    (tmp_path / "scenes").mkdir()
    return tmp_path, pkg


def _scene(root: Path, name="pick.yaml", **kwargs) -> Path:
    path = root / "scenes" / name
    path.write_text(scene_text(**kwargs))
    return path


def test_ros_package_plans_pick_up_a_cup_without_edits(workspace):
    root, pkg = workspace
    before = _digest(pkg)
    scene = load_scene(_scene(root))
    assert scene.robot.start["elbow_joint"] == pytest.approx(1.5708)  # "ready", an SRDF group_state
    prepared = prepare_model(scene.robot.model, scene.robot.packages)  # what the world parses
    assert len(prepared.converted) == 25 and all(Path(p).suffix == ".obj" for p in prepared.meshes.values())
    world = DrakeWorld(scene)
    solved = 0
    for seed in range(3):
        report = api.plan(scene, "pick up a cup", seed=seed, world=world, **BY_COUNTS)
        if not report.result.solved:
            continue
        solved += 1
        res = report.result
        fine = report.settings.planner.resolution / 10
        assert path_is_valid(world.space, world, res.path, fine) == -1, f"seed {seed}: path collides at {fine:g}"
        z = world.frame_pose("tool_tcp", res.path[-1]).rotation()[:, 2]
        if res.goal_region.label == "top":
            assert z @ [0, 0, -1] > np.cos(0.011)  # the z-forward tool points down at the cup
        elif res.goal_region.label == "angled":  # slanted 20-50 deg from straight down (issue 34)
            assert np.cos(np.radians(50) + 0.011) < z @ [0, 0, -1] < np.cos(np.radians(20) - 0.011)
        else:
            assert abs(z[2]) < np.sin(0.011)  # a side grasp approaches horizontally
    assert solved >= 2, f"solved {solved}/3"
    assert _digest(pkg) == before  # nothing in the robot's package was touched


def test_without_the_srdf_the_start_collides_and_allowed_collisions_fixes_it(workspace):
    root, _ = workspace
    ready = "{shoulder_pan_joint: 0, shoulder_lift_joint: -1.5708, elbow_joint: 1.5708, wrist_1_joint: -1.5708, wrist_2_joint: -1.5708, wrist_3_joint: 0}"
    text = scene_text().replace(f"  srdf: ../{PACKAGE}/config/my_arm.srdf\n", "").replace("start: ready", f"start: {ready}")
    (root / "scenes" / "bare.yaml").write_text(text)
    world = DrakeWorld(load_scene(root / "scenes" / "bare.yaml"))
    assert not world.config_free(world.start)
    assert ("fts_robotside", "wrist_2_link") in {tuple(sorted(p)) for p in world.colliding_pairs(world.start)}
    (root / "scenes" / "allowed.yaml").write_text(text.replace("objects:", "  allowed_collisions: [[wrist_2_link, fts_robotside]]\nobjects:"))
    assert DrakeWorld(load_scene(root / "scenes" / "allowed.yaml")).config_free(world.start)
    (root / "scenes" / "typo.yaml").write_text(text.replace("objects:", "  allowed_collisions: [[wrist_2, fts_robotside]]\nobjects:"))
    with pytest.raises(SceneError, match=r"robot.allowed_collisions: no link 'wrist_2' in the robot model"):
        DrakeWorld(load_scene(root / "scenes" / "typo.yaml"))


def test_unknown_package_is_one_line_saying_what_to_do(tmp_path, monkeypatch, capsys):
    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    make_package(tmp_path, mesh_uri="package://arm_meshes/meshes")  # meshes named through another package
    (tmp_path / "scenes").mkdir()
    scene = _scene(tmp_path)
    assert main(["plan", str(scene), "pick up a cup"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "unknown package 'arm_meshes'" in err and "--package arm_meshes=DIR" in err
    # the same package given on the command line, or found through ROS_PACKAGE_PATH
    folder = tmp_path / PACKAGE
    assert main(["ground", str(scene), "pick up a cup", "--package", f"arm_meshes={folder}"]) == 0
    robot = load_scene(scene, {"packages": {"arm_meshes": str(folder)}}).robot
    assert prepare_model(robot.model, robot.packages).packages == {"arm_meshes": str(folder)}
    assert DrakeWorld(load_scene(scene, {"packages": {"arm_meshes": str(folder)}})).config_free(ROS_READY)
    (folder / "package.xml").write_text((folder / "package.xml").read_text().replace(PACKAGE, "arm_meshes"))
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path))
    assert DrakeWorld(load_scene(scene)).config_free(ROS_READY)  # found through ROS_PACKAGE_PATH
