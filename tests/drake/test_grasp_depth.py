"""Issue 34: every grasp puts the closing fingers around the object by its stated depth, on every bundled robot.

A top grasp's depth was measured above the top face: the Panda's fingertips, 9 mm past its TCP, closed
above a can's rim. Here the fingers are the grippers' own collision pads (read from the model in Drake,
not from robot.yaml); each grasp region is taken at both ends of its depth range, and the box the pads
sweep as they close must overlap the object by the template's ``depth`` along the approach axis.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pydrake")

from grounding.regions import regions_for, type_definitions  # noqa: E402
from lazyground.drake.world import DrakeWorld  # noqa: E402
from lazyground.robots.end_effector import X_NT, end_effector_of  # noqa: E402
from lazyground.scene import parse_scene  # noqa: E402
from tests.unit.test_grounding import REPO  # noqa: E402

ROBOTS = {"fetch": "base: {xyz: [0, 0, 0]}\n", "panda": "base: {xyz: [0, 0, 0]}\n  base_link: panda_link0\n",
          "ur5e": "base: {xyz: [0, 0, 0]}\n"}
OBJECTS = """\
objects:
- {id: can_1, type: can, geometry: {cylinder: {radius: 0.033, length: 0.12}}, pose: {xyz: [0.6, 0.0, 0.06]}}
- {id: box_1, type: box, geometry: {box: [0.05, 0.06, 0.1]}, pose: {xyz: [0.6, 0.3, 0.05], rpy: [0, 0, 0.3]}}
"""
TEMPLATE_OF = {"top": "top", "face": "side_faces", "side": "side_around", "angled": "angled"}
STEP = 0.0005  # m: the overlap's resolution along the approach axis


def _scene(robot: str):
    text = f"name: grasp_{robot}\nrobot:\n  model: {robot}\n  {ROBOTS[robot]}{OBJECTS}"
    return parse_scene(text, f"grasp_{robot}.yaml", REPO)


def _finger_corners_T(world, frame: str) -> np.ndarray:
    """Corners (N, 3) of the fingers' collision boxes in the tool frame (bodies named *finger*)."""
    diagram = world.diagram
    plant, inspector = diagram.plant(), diagram.scene_graph().model_inspector()
    context = plant.GetMyContextFromRoot(diagram.CreateDefaultContext())
    T = plant.GetFrameByName(frame)
    corners = []
    for index in plant.GetBodyIndices(world.robot):
        body = plant.get_body(index)
        if "finger" not in body.name():
            continue
        X_TB = plant.CalcRelativeTransform(context, T, body.body_frame()).GetAsMatrix4()
        for gid in plant.GetCollisionGeometriesForBody(body):
            shape = inspector.GetShape(gid)
            half = np.array([shape.width(), shape.depth(), shape.height()]) / 2
            X_TG = X_TB @ inspector.GetPoseInFrame(gid).GetAsMatrix4()
            for signs in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T:
                corners.append((X_TG @ np.append(signs * half, 1.0))[:3])
    assert len(corners) >= 16, f"{frame}: no finger pads found"
    return np.array(corners)


def _overlap(region, v, obj, corners_N, X_TN, centre_line=False) -> float:
    """How far (m, along the approach axis) the box the pads sweep when closing overlaps the object
    (``centre_line``: the sweep's middle plane across the closing axis, where a tilted approach's line runs)."""
    lo, hi = corners_N.min(axis=0), corners_N.max(axis=0)
    xs = np.arange(lo[0], hi[0] + STEP / 2, STEP)
    zs = [(lo[2] + hi[2]) / 2] if centre_line else np.linspace(lo[2], hi[2], 5)
    grid = np.array(np.meshgrid(xs, np.linspace(lo[1], hi[1], 15), zs, indexing="ij"))
    p_N = grid.reshape(3, -1).T
    X_WT = region.pose_in_world(v).matrix()
    X_OW = np.linalg.inv(obj.pose.pose().matrix())
    p_O = (X_OW @ X_WT @ X_TN @ np.c_[p_N, np.ones(len(p_N))].T)[:3].T
    inside = np.array([obj.geometry.contains(p, margin=0.0) for p in p_O]).reshape(grid.shape[1:])
    return float(inside.any(axis=(1, 2)).sum() * STEP)


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_closing_fingers_overlap_the_object_by_the_stated_depth(robot):
    scene = _scene(robot)
    world = DrakeWorld(scene)
    ee = end_effector_of(scene.robot)
    X_TN = np.linalg.inv(X_NT(ee).matrix())
    corners_T = _finger_corners_T(world, ee.frame)
    corners_N = (np.linalg.inv(X_TN) @ np.c_[corners_T, np.ones(len(corners_T))].T)[:3].T
    kinds = set()
    for obj in scene.objects:
        specs = {"angled" if "tilt" in s else s["template"]: s for s in type_definitions(scene)[obj.type]["pick"]}
        for region in regions_for(obj, "pick", f"pick:{obj.id}", scene):
            template = TEMPLATE_OF[region.label.split()[0]]
            d0, d1 = specs[template]["depth"]
            mid = (np.asarray(region.lower) + np.asarray(region.upper)) / 2
            if template == "angled":  # the depth axis is the line's vertical shift (v[2]); at every tilt within the range
                for tilt in (region.lower[4], 0.0, region.upper[4]):
                    for end, sign in ((region.lower[2], -1), (region.upper[2], 1)):
                        v = mid.copy()
                        v[2], v[4] = end, tilt
                        got = _overlap(region, v, obj, corners_N, X_TN, centre_line=True)
                        assert d0 - 0.002 <= got <= d1 + 0.002, f"{robot} {region.id} tilt {tilt:.2f}: the fingers overlap {got:.4f} m"
                        # the line shifted u = half the range x cos t1 enters u / cos(tilt) earlier or later: the range's end at t1
                        want = (d0 + d1) / 2 + sign * (d1 - d0) / 2 * np.cos(region.upper[4]) / np.cos(tilt)
                        assert abs(got - want) <= 0.002, f"{robot} {region.id} tilt {tilt:.2f}: the fingers overlap {got:.4f} m, want {want:.4f}"
            else:
                for end, want in ((region.lower[0], d0), (region.upper[0], d1)):
                    v = mid.copy()
                    v[0] = end
                    got = _overlap(region, v, obj, corners_N, X_TN)
                    assert abs(got - want) <= 0.002, f"{robot} {region.id}: the fingers overlap {got:.4f} m, want {want}"
            kinds.add((obj.type, template))
    assert kinds == {("can", "top"), ("can", "side_around"), ("can", "angled"), ("box", "side_faces"), ("box", "top"), ("box", "angled")}
