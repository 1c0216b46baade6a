"""Issue #28: descriptions as they come plan "pick up a cup" unedited (tests/drake/robot_corpus.py).

Each feature's robot plans over seeds (a success rate, iteration-capped), every shortened path
re-checked at a tenth of the planner's edge resolution and no joint swept more than pi.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pydrake")

from lazyground.api import plan  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.planning import path_is_valid  # noqa: E402
from lazyground.planning.turns import sweeps  # noqa: E402
from lazyground.scene import load_scene  # noqa: E402
from lazyground.typed_yaml import SceneError  # noqa: E402
from tests.drake import robot_corpus as corpus  # noqa: E402

SEEDS = (0, 1, 2)
MAX_ITERATIONS = 3000


def _plans(scene, min_rate: float = 2 / 3):
    world = DrakeWorld(scene, visual=False)
    fine = scene.planner.edge_resolution / 10
    solved, notes = 0, set()
    for seed in SEEDS:
        report = plan(scene, "pick up a cup", seed=seed, world=world, max_iterations=MAX_ITERATIONS)
        notes.update(report.notes)
        if not report.result.solved:
            continue
        solved += 1
        assert path_is_valid(world.space, world, report.result.path, fine) == -1, f"seed {seed}: path collides at {fine:g}"
        path = report.outcome.steps[0].motion.shortcut.path
        assert path_is_valid(world.space, world, path, fine) == -1, f"seed {seed}: shortened path collides at {fine:g}"
        swept = sweeps(path, world.space.wrap).max()
        assert swept <= np.pi, f"seed {seed}: a joint sweeps {swept:.2f} rad"
    assert solved / len(SEEDS) >= min_rate, f"{solved} of {len(SEEDS)} seeds solved"
    return notes


def test_xacro_with_required_argument_and_find_plans(tmp_path):
    model = corpus.xacro_arm(tmp_path)
    with pytest.raises(SceneError, match="xacro argument 'name' is required.*--xacro-arg name=VALUE"):
        load_and_build = load_scene(corpus.cup_scene(tmp_path, model, "xacro_missing"))
        DrakeWorld(load_and_build, visual=False)
    scene = load_scene(corpus.cup_scene(tmp_path, model, "xacro_arm", xacro_args={"name": "my_arm", "tcp_offset": 0.125}))
    _plans(scene)


def test_xacro_expansion_is_cached_by_content(tmp_path, monkeypatch):
    from lazyground.robots import xacro_file

    monkeypatch.setenv("LAZYGROUND_CACHE", str(tmp_path / "cache"))
    model = corpus.xacro_arm(tmp_path)
    packages = {corpus.PACKAGE: model.parents[1]}
    first = xacro_file.expand_xacro(model, {"name": "a"}, packages)
    assert 'name="b"' in xacro_file.expand_xacro(model, {"name": "b"}, packages)  # other arguments: another entry
    calls = []
    monkeypatch.setattr(xacro_file, "_run_xacro", lambda *a: calls.append(a) or ("", []))
    assert xacro_file.expand_xacro(model, {"name": "a"}, packages) == first and not calls  # a hit
    macro = model.parent / "arm_macro.xacro"
    macro.write_text(macro.read_text().replace("0.076", "0.077"))  # an included file changed: expanded again
    xacro_file.expand_xacro(model, {"name": "a"}, packages)
    assert len(calls) == 1


def test_sdf_with_undeclared_drake_prefix_plans(tmp_path):
    model = corpus.sdf_arm(tmp_path)
    assert "xmlns:drake" not in model.read_text()
    _plans(load_scene(corpus.cup_scene(tmp_path, model, "sdf_arm")))


def test_mimic_finger_joints_plan(tmp_path):
    _plans(load_scene(corpus.cup_scene(tmp_path, corpus.mimic_arm(tmp_path), "mimic_arm")))


def test_continuous_joints_with_huge_limits_wrap(tmp_path):
    scene = load_scene(corpus.cup_scene(tmp_path, corpus.continuous_arm(tmp_path), "continuous_arm"))
    world = DrakeWorld(scene, visual=False)
    wrapped = dict(zip(world.space.names, world.space.wrap))
    assert wrapped["shoulder_pan_joint"] and wrapped["wrist_3_joint"] and not wrapped["elbow_joint"]
    assert any("continuous joints wrap" in n for n in world.model_notes)
    _plans(scene)


def test_floating_base_is_welded_at_the_origin_with_a_note(tmp_path, capsys):
    from lazyground.cli import main

    model = corpus.mimic_arm(tmp_path)  # no link named world, no robot.base: the model floats
    notes = _plans(load_scene(corpus.cup_scene(tmp_path, model, "floating", floating=True)))
    note = "the model is not welded to the world: base_link welded at the origin"
    assert any(note in n for n in notes)
    assert main(["check-robot", str(model)]) == 0 and note in capsys.readouterr().out  # check-robot says what plan does


def test_unloadable_visual_meshes_do_not_block_planning(tmp_path):
    scene = load_scene(corpus.cup_scene(tmp_path, corpus.visual_meshes_arm(tmp_path), "visual_meshes"))
    world = DrakeWorld(scene, visual=True)  # the viewer's world: visuals drawn from collision geometry
    assert any("drawn from their collision geometry" in n for n in world.model_notes)
    _plans(scene)


def test_duplicate_transmissions_and_ros_tags_are_stripped(tmp_path):
    _plans(load_scene(corpus.cup_scene(tmp_path, corpus.transmission_arm(tmp_path), "transmissions")))


def test_self_colliding_hand_is_reported_then_allowed_pairs_written_and_it_plans(tmp_path, capsys):
    import yaml

    from lazyground.cli import main

    model = corpus.self_colliding_arm(tmp_path)
    assert main(["check-robot", str(model)]) == 2
    assert "1 link pair(s) touch in at least 95%" in capsys.readouterr().out.splitlines()[-1]
    scene = load_scene(corpus.cup_scene(tmp_path, model, "hand_start"))
    report = plan(scene, "pick up a cup", seed=0, max_iterations=200)
    assert not report.result.solved  # every configuration collides: nothing plans
    allowed = tmp_path / "allowed.yaml"
    assert main(["check-robot", str(model), "--write-allowed", str(allowed), "--samples", "300", "--seed", "1"]) == 0
    pairs = yaml.safe_load(allowed.read_text())["allowed_collisions"]
    assert ["gripper_left_finger", "gripper_right_finger"] in pairs
    assert main(["check-robot", str(model), "--write-allowed", str(tmp_path / "hand.srdf"), "--samples", "50"]) == 0
    assert 'link1="gripper_left_finger" link2="gripper_right_finger" reason="Default"' in (tmp_path / "hand.srdf").read_text()
    _plans(load_scene(corpus.cup_scene(tmp_path, model, "hand", allowed_collisions=pairs)))
    _plans(load_scene(corpus.cup_scene(tmp_path, model, "hand_srdf", srdf=str(tmp_path / "hand.srdf"))))


def test_a_xacro_robot_with_a_robot_yaml_plans_and_imports_moveit_scenes(tmp_path, capsys):
    import yaml

    from lazyground.cli import main
    from tests.unit.test_moveit_import import ONE_WALL

    model = corpus.xacro_arm(tmp_path)
    (model.parent / "robot.yaml").write_text(yaml.safe_dump({
        "model": model.name, "base_link": "base_link", "planned_joints": corpus.ARM, "end_effector": corpus.END_EFFECTOR,
        "start": "ready", "named_poses": {"ready": corpus.READY}, "xacro_args": {"name": "from_robot_yaml"}}))
    scene = tmp_path / "scene.yaml"
    scene.write_text(yaml.safe_dump({"name": "s", "robot": {"model": str(model), "base": {"xyz": [0, 0, 0]}},
                                     "planner": {"max_iterations": 3000, "time_limit": 120.0},
                                     "objects": yaml.safe_load(corpus.cup_scene(tmp_path, model, "x").read_text())["objects"]}))
    assert main(["plan", str(scene), "pick up a cup", "--seed", "0", "--xacro-arg", "tcp_offset=0.125"]) == 0
    assert main(["check-robot", str(model)]) == 0 and "(base none" not in capsys.readouterr().out
    source = tmp_path / "moveit.yaml"
    source.write_text(ONE_WALL)
    out = tmp_path / "imported.yaml"
    assert main(["import-moveit", str(source), "-o", str(out), "--robot", str(model), "--xacro-arg", "name=imported"]) == 0
    assert yaml.safe_load(out.read_text())["robot"]["xacro_args"] == {"name": "imported"}
    assert main(["check-robot", str(model), "--xacro-arg", "tcp_offset=oops"]) == 2
    assert "xacro" in capsys.readouterr().err


def test_a_gripper_from_its_own_package_mounts_on_the_flange_with_its_end_effector_and_mimic(tmp_path):
    arm, gripper = corpus.arm_and_gripper(tmp_path)
    scene = load_scene(corpus.cup_scene(tmp_path, arm, "tools", end_effector=None,
                                        tools=[{"model": str(gripper), "parent": "tool0", "pose": {"xyz": [0, 0, 0]}}],
                                        start={**corpus.READY, "finger_joint": 0.005}))  # 5 mm wider open
    assert scene.robot.end_effector.frame == "tool_tcp"  # from the gripper's robot.yaml
    world = DrakeWorld(scene, visual=False)
    names = list(world.plant.GetPositionNames(world.robot, add_model_instance_prefix=False, always_add_suffix=False))
    assert world.q_full[names.index("right_finger_joint")] == pytest.approx(0.005)  # the mimic follows its leader
    _plans(scene)
    bad = corpus.cup_scene(tmp_path, arm, "tools_bad", tools=[{"model": str(gripper), "parent": "flange_x"}])
    with pytest.raises(SceneError, match=r"robot.tools\[0\].parent: no link 'flange_x' in the robot model"):
        DrakeWorld(load_scene(bad), visual=False)


def test_mimic_joints_follow_their_leader_in_the_self_collision_samples(tmp_path):
    # both fingers slide along +y, the right one a mimic of the left, their pads overlapping: held together by the
    # linkage they touch in every pose; sampled independently over 0.2 m they would seldom touch
    text = corpus._without_filter_groups(corpus.ur5e_text())
    text = text.replace('<joint name="gripper-left_finger" type="fixed">',
                        '<joint name="finger_joint" type="prismatic"><axis xyz="0 1 0"/><limit lower="0" upper="0.2" effort="1" velocity="1"/>')
    text = text.replace('<joint name="gripper-right_finger" type="fixed">',
                        '<joint name="right_finger_joint" type="prismatic"><axis xyz="0 1 0"/>'
                        '<limit lower="0" upper="0.2" effort="1" velocity="1"/><mimic joint="finger_joint"/>')
    text = text.replace('<origin xyz="0 -0.0425 0.08" rpy="0 0 0"/>', '<origin xyz="0 0.05 0.08" rpy="0 0 0"/>')
    from lazyground.drake.check_robot import check_robot

    report = check_robot(corpus._urdf(tmp_path, "linkage.urdf", text), samples=100)
    assert not report.ok and "gripper_left_finger-gripper_right_finger" in report.problems[0]
