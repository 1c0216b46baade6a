"""Meshcat: the HTML replay, the live view through the CLI, and pick-and-place steps."""

import textwrap

import numpy as np
import pytest

from lazyground.viz import meshcat_view
from lazyground.viz.meshcat_view import EXTERNAL_SCRIPT, FPS, PAUSE_SECONDS, STEP_SECONDS

from .conftest import PARKING


def test_html_replay_is_self_contained(parking, tmp_path):
    scene, report = parking
    out = tmp_path / "r.html"
    size = meshcat_view.write_html(report, scene, out)
    html = out.read_text()
    assert size == out.stat().st_size
    assert 500_000 < size < 10_000_000
    assert "<script" in html and "MeshCat" in html
    assert not EXTERNAL_SCRIPT.search(html)  # tests/viz/test_browser.py also checks no request leaves the file


def test_external_script_pattern_can_fire():
    assert EXTERNAL_SCRIPT.search('<script src="https://cdn.example.com/three.js"></script>')
    assert EXTERNAL_SCRIPT.search("<script type='module' src=//cdn.example.com/x.js>")
    assert not EXTERNAL_SCRIPT.search('<script type="text/javascript">var a = "https://x";</script>')


def test_draw_records_the_car_and_overlays(parking):
    from pydrake.geometry import Meshcat

    scene, report = parking
    meshcat = Meshcat()
    seconds = meshcat_view.draw(report, scene, meshcat)
    duration = report.motion.trajectory.duration  # the replay's clock is the trajectory's (#16)
    assert seconds == pytest.approx(duration + PAUSE_SECONDS, abs=1e-9)
    for path in ("/drake/robot0/car/car_body", "/lazyground/step0/tree/edges", "/lazyground/step0/path",
                 "/lazyground/step0/raw_path",
                 "/lazyground/step0/goal_regions/spot_b9", "/lazyground/step0/goal_samples/0/arrow"):
        assert meshcat.HasPath(path), path
    assert meshcat.HasPath("/lazyground/step0/tree/failed_goal_biased_from") == (len(report.result.failed_from) > 0)
    animation = meshcat.get_mutable_recording()
    assert animation.frame(seconds) >= FPS * duration  # the car's motion was recorded to the end


def test_cli_meshcat_loop_once_and_html(tmp_path, capsys):
    from lazyground.cli import main

    html = tmp_path / "c.html"
    rc = main(["plan", str(PARKING), "park", "--seed", "0", "--time-limit", "1000", "--meshcat", "--loop-once", "--html", str(html)])
    out = capsys.readouterr().out
    assert rc == 0
    assert "meshcat: http://" in out
    assert "Ctrl-C" not in out and "--loop-once" in out  # issue 34: it said "press Ctrl-C to stop" and exited
    assert html.stat().st_size > 500_000


FETCH_SCENE = """\
    name: fetch_can_viz
    robot:
      model: fetch
      base: {xyz: [0.0, 0.0, 0.0]}
      planned_joints: [torso_lift_joint, shoulder_pan_joint, shoulder_lift_joint, upperarm_roll_joint,
        elbow_flex_joint, forearm_roll_joint, wrist_flex_joint, wrist_roll_joint]
      end_effector: gripper_link
      start: {torso_lift_joint: 0.05, shoulder_pan_joint: 1.32, shoulder_lift_joint: 1.4, upperarm_roll_joint: -0.2,
        elbow_flex_joint: 1.72, wrist_flex_joint: 1.66}
    objects:
    - {id: can1, type: can, geometry: {cylinder: {radius: 0.035, length: 0.115}}, pose: {xyz: [0.8, 0.0, 0.72]}, color: red}
    - {id: table, type: table, geometry: {box: [0.6, 0.8, 0.03]}, pose: {xyz: [0.8, 0.0, 0.65]}}
"""


def _step(world, g, q0, q1, regions, seed=0):
    """A hand-made solved step from q0 to q1 (no planning: the drawing is under test)."""
    from lazyground.plan_report import PlanReport
    from lazyground.planning.problem import GoalSample, PlanResult, PlanStatus
    from lazyground.settings import RunSettings

    mid = (q0 + q1) / 2
    sample = GoalSample(q=q1, region=0, weight=0.3)
    tree = (np.array([q0, mid, q1, q0 + 0.1]), np.array([-1, 0, 1, 0]), np.array([False, True, True, False]))
    result = PlanResult(PlanStatus.SOLVED, seed, np.array([q0, mid, q1]), sample, regions[0], 3, 4, [sample], 0, 0.0, 0.0, 0.0,
                        regions=tuple(regions), tree=tree, failed_from=np.array([3]))
    return PlanReport("step", "fetch_can_viz", seed, RunSettings(), g, result, world.space.names, 0.0, 0.0)


def fetch_can_set_up(tmp_path):
    """The small Fetch scene with one can, grounded for "pick up the can", and three configurations
    (start, grasp, place) that pick-and-place replays are drawn through."""
    import grounding

    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    path = tmp_path / "fetch_can_viz.yaml"
    path.write_text(textwrap.dedent(FETCH_SCENE))
    scene = load_scene(path)
    world = DrakeWorld(scene, visual=False)
    q0 = world.start
    q1 = q0 + np.array([0.1, -1.0, -0.8, 0.0, -0.5, 0.0, -0.5, 0.0])
    q2 = q1 + np.array([0.0, 0.4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    return scene, world, grounding.ground("pick up the can", scene), (q0, q1, q2)


def test_pick_and_place_steps_replay_in_turn_with_the_carried_object(tmp_path):
    from pydrake.geometry import Meshcat

    from lazyground.geometry import Pose

    scene, world, g, (q0, q1, q2) = fetch_can_set_up(tmp_path)
    regions = g.goal_regions
    lift = np.array([q1, q1 + [0.05, 0, 0, 0, 0, 0, 0, 0]])
    pick, place = _step(world, g, q0, q1, regions), _step(world, g, lift[-1], q2, regions)
    from dataclasses import replace

    from lazyground.tasks import Grasp, Lift, Outcome, Step

    grasp = Grasp("can1", regions[0].id, regions[0].label, "gripper_link", Pose(), Pose())
    steps = (Step("pick can1", pick.result), Step("place can1", place.result, grasp=grasp, lift=Lift(lift, 0.05)))
    report = replace(pick, outcome=Outcome(pick.result, steps, world.space.names, lift=Lift(lift, 0.05)))
    segments = meshcat_view._segments(report, scene)
    assert [s.attached.object.id if s.attached else None for s in segments] == [None, "can1"]
    assert np.allclose(segments[1].motion[0], lift[0]) and np.allclose(segments[1].motion[-1], q2)

    meshcat = Meshcat()
    seconds = meshcat_view.draw(report, scene, meshcat)
    assert seconds == pytest.approx(2 * (STEP_SECONDS + PAUSE_SECONDS), abs=3 / FPS)
    assert meshcat.HasPath("/drake/robot0/can1")  # on the table while picking
    assert not meshcat.HasPath("/drake/robot1/can1")  # ... and on the gripper while placing:
    assert any(meshcat.HasPath(f"/drake/robot1/fetch/gripper_link/{p}") for p in ("carried/can1", "fetch/carried/can1"))
    for k in (0, 1):
        assert meshcat.HasPath(f"/lazyground/step{k}/goal_regions/can1_top")
        assert meshcat.HasPath(f"/lazyground/step{k}/tree/failed_goal_biased_from")
    out = tmp_path / "pp.html"
    assert meshcat_view.write_html(report, scene, out) > 500_000


def test_several_objects_replay_each_step_in_the_scene_the_earlier_steps_left(tmp_path):
    """An object placed in step 2 stands where it was put in steps 3 and 4 (#30), not where it started."""
    from dataclasses import replace

    from lazyground.geometry import Pose
    from lazyground.tasks import Grasp, Outcome, Placement, Step

    scene, world, g, (q0, q1, q2) = fetch_can_set_up(tmp_path)
    regions = g.goal_regions
    pick, place = _step(world, g, q0, q1, regions), _step(world, g, q1, q2, regions)
    X_WO = Pose((0.3, 0.1, 0.8))
    grasp = Grasp("can1", regions[0].id, regions[0].label, "gripper_link", Pose(), Pose())
    steps = (Step("pick can1", pick.result), Step("place can1", place.result, grasp=grasp,
                                                   placement=Placement("table/surface", "table", X_WO)),
             Step("pick can1", pick.result), Step("place can1", place.result, grasp=grasp))
    report = replace(pick, outcome=Outcome(pick.result, steps, world.space.names))
    segments = meshcat_view._segments(report, scene)
    original = scene.object("can1").pose.xyz
    assert [s.scene.object("can1").pose.xyz for s in segments] == [original, original, X_WO.xyz, X_WO.xyz]
    assert np.allclose([segments[2].scene.robot.start[n] for n in world.space.names], q2)  # where step 2 ended
