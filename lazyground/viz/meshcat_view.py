"""A planned grounding in Drake's Meshcat: live on localhost, or one self-contained HTML replay.

What is drawn (colours from :mod:`lazyground.viz.style`, as in the paper's Figs. 4 and 6):

* the scene and the robot (Drake's MeshcatVisualizer on the scene's
  ``DrakeWorld``), the robot animated along the path in a Meshcat recording;
  a pick-and-place report animates its ``steps`` one after the other, each in
  its own world, only the current one visible: the pick, then the lift-off and
  the place with the object riding on the gripper (each step's ``grasp`` says
  what it carries; the outcome's ``lift`` leads into the place step);
* the goal regions, translucent green: the object's box for configuration
  regions (a parking spot), the region's box in its frame for workspace and
  placement regions;
* the goal samples coloured by their final reward-penalty weight, at the
  *tracer* point: the end effector for arms, the base for mobile robots
  (with an arrow along its heading and, for the car, its footprint);
* the tree's edges (dark blue) in the tracer's workspace, the nodes added by
  goal-biased extensions (blue; with the bidirectional planner, every node of
  the goal trees) and the origins of failed goal-biased extensions (red), and
  the solution path (light blue).
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np
from pydrake.geometry import Box, Meshcat, MeshcatAnimation, MeshcatVisualizer, MeshcatVisualizerParams, Rgba, Sphere
from pydrake.math import RigidTransform
from pydrake.perception import BaseField, Fields, PointCloud

from lazyground.drake.world import Attachment, DrakeWorld, rigid_transform
from lazyground.robots.end_effector import frame_of
from lazyground.tasks.replay import scenes_per_step
from lazyground.viz.replay_page import Layout, decorate
from lazyground.viz.shapes import draw_tube
from lazyground.viz.style import (
    CAR_FOOTPRINT, FAILED_RGBA, GOAL_BIASED_RGBA, PATH_DARK_RGBA, PATH_RGBA, REGION_RGBA, REVERSE_RGBA, TREE_RGBA,
    weight_rgba,
)
from lazyground.viz.trace import frames_in_time, resample_path, tree_edges

FPS = 30
STEP_SECONDS = 4.0  # animation length of a step without a timed trajectory (else: its real duration)
RAW_PATH_ALPHA = 0.3  # the planner's raw path, drawn faintly beside the shortened one
PAUSE_SECONDS = 0.5  # hold at the end of a step
ROOT = "/lazyground"
CAMERA_DISTANCE = 1.75  # x the drawn extent's radius; the page's side panel leaves the view ~70 % of the width
EXTERNAL_SCRIPT = re.compile(r"<script[^>]*\bsrc\s*=\s*[\"']?(https?:)?//", re.IGNORECASE)


def write_html(report, scene, path) -> int:
    """Write the self-contained HTML replay of ``report``; returns the bytes written.

    Raises:
        RuntimeError: Meshcat's page refers to an external script (it would not open offline).
    """
    meshcat = Meshcat()
    layout = draw_layout(report, scene, meshcat)
    html = meshcat.StaticHtml()
    if EXTERNAL_SCRIPT.search(html):
        raise RuntimeError("Meshcat's static HTML refers to an external script")
    html = decorate(html, report, layout)  # title and the explaining side panel (replay_page)
    data = html.encode("utf-8")
    Path(path).write_bytes(data)
    return len(data)


def show_live(report, scene, loop_once: bool, say: Callable[[str], None]) -> None:
    """Serve ``report`` in a live Meshcat on localhost until Ctrl-C (or return at once with ``loop_once``);
    ``say`` gets the address and the stop line (the CLI prints them)."""
    meshcat = Meshcat()
    seconds = draw(report, scene, meshcat)
    until = "drawn once (--loop-once): the server stops now" if loop_once else "press Ctrl-C to stop"
    say(f"meshcat: {meshcat.web_url()} (replay {seconds:.1f} s; {until})")
    if loop_once:
        return
    try:
        while True:
            time.sleep(0.5)
    except KeyboardInterrupt:
        say("meshcat: stopped")


def draw(report, scene, meshcat: Meshcat) -> float:
    """Draw ``report`` into ``meshcat`` and record the robot's motion; returns the replay length in seconds."""
    return draw_layout(report, scene, meshcat, hide_tree=False).seconds  # live: no page, no button to show it


def draw_layout(report, scene, meshcat: Meshcat, hide_tree: bool = True) -> Layout:
    """:func:`draw`, returning what the page's side panel needs (step windows, tree paths).

    ``hide_tree``: the search tree starts hidden (the page's button shows it); it covers the lot and the objects
    (issue 34: a parking page opened on a thicket of tree edges)."""
    meshcat.Delete()
    meshcat.DeleteRecording()
    meshcat.StartRecording(frames_per_second=FPS, set_visualizations_while_recording=True)
    segments = _segments(report, scene)
    views = [_StepView(s, scene, meshcat, f"robot{k}") for k, s in enumerate(segments)]
    nodes = sum(len(v.report.result.tree[0]) for v in views if v.report.result.tree is not None)
    for k, view in enumerate(views):
        view.draw_overlays(f"{ROOT}/step{k}", hide_tree)
    t, windows = 0.0, []
    for k, view in enumerate(views):
        for j, other in enumerate(views if len(views) > 1 else []):  # only the current step's world is visible
            meshcat.SetProperty(f"/drake/{other.prefix}", "visible", j == k, time_in_recording=t)
        end = view.animate(t)
        windows.append((step_label(report, k, len(views)), t, end))
        t = end + PAUSE_SECONDS
    meshcat.StopRecording()
    animation = meshcat.get_mutable_recording()
    animation.set_loop_mode(MeshcatAnimation.LoopMode.kLoopRepeat)
    animation.set_autoplay(True)
    meshcat.PublishRecording()
    if not views[0].tracer.arm:  # a 10 m grid at the origin only clutters a parking lot
        meshcat.SetProperty("/Grid", "visible", False)
    _set_camera(meshcat, views, report)
    trees = tuple(f"{ROOT}/step{k}/tree" for k, v in enumerate(views) if v.report.result.tree is not None)
    return Layout(t, tuple(windows), trees, nodes, hide_tree and bool(trees), views[0].tracer.arm)


@dataclass(frozen=True)
class _Segment:
    """One animated step: its report, the object its robot carries, the motion to replay, the scene it plays in."""

    report: object
    attached: Attachment | None
    motion: np.ndarray | None
    trajectory: object = None  # the step's timed Trajectory (lazyground.motion): the replay's clock
    scene: object = None  # objects placed by earlier steps where they were put (None: the request's scene)


def _segments(report, scene) -> list[_Segment]:
    """The steps to replay: one for a plain plan; pick, then lift and place (carrying) for pick and place,
    each in the scene as the steps before it left it (several objects: placed objects where they were put)."""
    if not report.steps:
        return [_Segment(report, None, report.result.path, _trajectory(report))]
    out = []
    scenes = scenes_per_step(report.outcome, scene)
    for step, before in zip(report.steps, scenes):
        g = step.grasp
        carried = Attachment(before.object(g.object_id), g.frame, g.X_GO) if g is not None else None
        motion = step.result.path
        if motion is not None and step.lift is not None:  # the lift-off leads into the place step
            motion = np.vstack([step.lift.path, motion[1:]])
        out.append(_Segment(step, carried, motion, _trajectory(step), before))  # the place step's trajectory starts with the lift
    return out


def _trajectory(report):
    return report.motion.trajectory if getattr(report, "motion", None) is not None else None


@dataclass(frozen=True)
class _Tracer:
    """The robot point whose workspace positions stand for configurations."""

    body: object  # a RigidBody of the world's plant
    p_BT: np.ndarray
    arm: bool  # an end effector (metres-scale markers) or a mobile base (car-scale markers)


class _StepView:
    """One planned step: its own DrakeWorld with a MeshcatVisualizer, and its overlays."""

    def __init__(self, segment: _Segment, scene, meshcat: Meshcat, prefix: str):
        report = segment.report
        scene = segment.scene if segment.scene is not None else scene
        self.report, self.motion, self.scene, self.meshcat, self.prefix = report, segment.motion, scene, meshcat, prefix
        self.trajectory = segment.trajectory
        params = MeshcatVisualizerParams(prefix=prefix, delete_on_initialization_event=False)

        def add_visualizer(builder):
            MeshcatVisualizer.AddToBuilder(builder.builder(), builder.scene_graph(), meshcat, params)

        self.world = DrakeWorld(scene, attached=segment.attached, extend_builder=add_visualizer)
        self.context = self.world.diagram.CreateDefaultContext()
        self.plant_context = self.world.plant.GetMyMutableContextFromRoot(self.context)
        self.tracer = _tracer(self.world, scene)
        res = report.result
        self.start = self.motion[0] if self.motion is not None else res.tree[0][0] if res.tree is not None else self.world.start
        self.scale = 0.02 if self.tracer.arm else 0.25  # marker size, metres

    # --- kinematics ----------------------------------------------------------------------
    def poses(self, qs) -> list[RigidTransform]:
        """World poses of the tracer point at planned configurations ``qs``."""
        frame = self.tracer.body.body_frame()
        X_BT = RigidTransform(self.tracer.p_BT)
        return [self.world.kinematics.X_WF(frame, q).multiply(X_BT) for q in self.world.full(np.atleast_2d(qs))]

    def points(self, qs) -> np.ndarray:
        """(3, n) tracer positions at ``qs``."""
        if len(qs) == 0:
            return np.zeros((3, 0))
        return np.array([X.translation() for X in self.poses(qs)]).T

    # --- drawing -------------------------------------------------------------------------
    def draw_overlays(self, path: str, hide_tree: bool = False) -> None:
        res = self.report.result
        self._draw_regions(f"{path}/goal_regions", res.regions)
        self._draw_samples(f"{path}/goal_samples", res.goal_samples)
        if res.tree is not None:
            nodes, parents, goal_biased = res.tree
            p = self.points(nodes)
            child, parent = tree_edges(parents)
            if len(child):
                # an arm's tree is a dense ball around the gripper: draw it see-through
                rgba = Rgba(*TREE_RGBA[:3], 0.35 if self.tracer.arm else 1.0)
                self.meshcat.SetLineSegments(f"{path}/tree/edges", p[:, parent], p[:, child], 1.0, rgba)
            self._points(f"{path}/tree/goal_biased", p[:, np.asarray(goal_biased, bool)], GOAL_BIASED_RGBA, 1.0)
            if res.failed_from is not None:
                self._points(f"{path}/tree/failed_goal_biased_from", p[:, np.unique(res.failed_from)], FAILED_RGBA, 1.5)
            if hide_tree:  # the page's button shows it
                self.meshcat.SetProperty(f"{path}/tree", "visible", False)
        if self.motion is not None:
            motion = getattr(self.report, "motion", None)  # a report's or a step's Motion
            car = motion is not None and motion.cusps is not None  # a car's path is already its curves, densely sampled
            qs = self.motion if car else resample_path(self.motion, 200, self.world.space.wrap)
            dense = self.points(qs)
            self.meshcat.SetLine(f"{path}/path", dense, 4.0, Rgba(*PATH_RGBA))
            # browsers draw WebGL lines one pixel wide whatever the width: a tube makes the path stand out
            stride = max(4, dense.shape[1] // 50)  # ~50 cylinders, however densely a car's path is sampled
            tube = np.column_stack([dense[:, ::stride], dense[:, -1:]]) if dense.shape[1] > 4 else dense
            draw_tube(self.meshcat, f"{path}/path_tube", tube, 0.5 * self.scale, Rgba(*PATH_RGBA))
            if car:
                self._draw_travel(f"{path}/direction_of_travel", qs)
        raw = self.report.motion.raw_path if getattr(self.report, "motion", None) is not None else None
        if raw is not None and not np.array_equal(raw, self.report.result.path):
            dense = resample_path(raw, 200, self.world.space.wrap)
            self.meshcat.SetLine(f"{path}/raw_path", self.points(dense), 2.0, Rgba(*PATH_RGBA[:3], RAW_PATH_ALPHA))

    def animate(self, t0: float) -> float:
        """Record the robot along its timed trajectory at real speed (else along the path in
        ``STEP_SECONDS``) from time ``t0``; returns the end time."""
        if self.trajectory is not None:
            qs = frames_in_time(self.trajectory, FPS)
        elif self.motion is None:
            qs = np.atleast_2d(self.start)
        else:
            qs = resample_path(self.motion, int(STEP_SECONDS * FPS) + 1, self.world.space.wrap)
        for i, q in enumerate(qs):
            self.context.SetTime(t0 + i / FPS)
            self.world.plant.SetPositions(self.plant_context, self.world.full(q))
            self.world.diagram.ForcedPublish(self.context)
        if self.trajectory is not None:
            return t0 + self.trajectory.duration
        return t0 + (len(qs) - 1) / FPS

    def _draw_travel(self, path: str, dense: np.ndarray, every: float = 1.5) -> None:
        """Arrowheads along a car's path about every ``every`` metres: forwards blue, reverse orange."""
        poses = self.poses(dense)
        p = np.array([X.translation() for X in poses])
        step = np.linalg.norm(np.diff(p, axis=0), axis=1)
        s = np.concatenate([[0.0], np.cumsum(step)])
        size = self.scale * 3.0
        for gear, rgba in ((1.0, PATH_DARK_RGBA), (-1.0, REVERSE_RGBA)):
            starts, ends = [], []
            for k in np.unique(np.searchsorted(s, np.arange(every / 2, s[-1], every))):
                if not 0 < k < len(p) or step[k - 1] <= 0:
                    continue
                u = (p[k] - p[k - 1]) / step[k - 1]
                if np.sign(u @ poses[k].rotation().matrix()[:, 0]) != gear:
                    continue
                side = np.cross([0.0, 0.0, 1.0], u)
                tip = p[k] + [0.0, 0.0, 0.05]
                for wing in (tip - size * u + 0.5 * size * side, tip - size * u - 0.5 * size * side):
                    starts.append(wing)
                    ends.append(tip)
            if starts:
                self.meshcat.SetLineSegments(f"{path}/{'forwards' if gear > 0 else 'reverse'}", np.array(starts).T,
                                             np.array(ends).T, 3.0, Rgba(*rgba))

    def _points(self, path: str, p: np.ndarray, rgba, size: float) -> None:
        if p.shape[1] == 0:
            return
        cloud = PointCloud(p.shape[1], Fields(BaseField.kXYZs))
        cloud.mutable_xyzs()[:] = p
        self.meshcat.SetObject(path, cloud, size * self.scale, Rgba(*rgba))

    def _draw_regions(self, path: str, regions) -> None:
        drawn = set()
        for region in regions:
            d = region.drawing(self.scene)
            if d.name in drawn:  # one box per drawing (a spot's forwards and reversing regions)
                continue
            drawn.add(d.name)
            name = f"{path}/{_safe(d.name)}"
            self.meshcat.SetObject(name, Box(*d.size), Rgba(*REGION_RGBA))
            self.meshcat.SetTransform(name, rigid_transform(d.X_WB))

    def _draw_samples(self, path: str, samples) -> None:
        if not samples:
            return
        poses = self.poses(np.array([s.q for s in samples]))
        for i, (s, X) in enumerate(zip(samples, poses)):
            rgba = Rgba(*weight_rgba(s.weight))
            name = f"{path}/{i}"
            self.meshcat.SetObject(f"{name}/point", Sphere(self.scale * 0.6), rgba)
            if not self.tracer.arm:  # the car's footprint at the sample, translucent
                x, y = CAR_FOOTPRINT
                self.meshcat.SetObject(f"{name}/footprint", Box(x, y, 0.04), Rgba(*weight_rgba(s.weight, 0.35)))
            length = self.scale * (4.0 if self.tracer.arm else 10.0)
            head = np.array([[length, 0, 0], [0.7 * length, 0.2 * length, 0], [0.7 * length, -0.2 * length, 0]]).T
            start = np.array([[0, 0, 0], head[:, 0], head[:, 0]]).T
            end = np.array([head[:, 0], head[:, 1], head[:, 2]]).T
            self.meshcat.SetLineSegments(f"{name}/arrow", start, end, 2.0, rgba)
            self.meshcat.SetTransform(name, X)


def step_label(report, k: int, n: int) -> str:
    """What step ``k`` of ``n`` does, for the page: "1. pick Can3", "2. place Can3 on table", or the chosen goal
    (several objects: every place step names its surface)."""
    if n == 1:
        return report.chosen.id if report.chosen is not None else report.request
    placement = report.steps[k].placement
    return f"{k + 1}. {report.steps[k].label}" + (f" on {placement.target}" if placement is not None else "")


def _tracer(world: DrakeWorld, scene) -> _Tracer:
    """The end effector if the robot has one, otherwise its base (lifted off the ground)."""
    plant = world.plant
    ee = frame_of(scene.robot)
    if plant.HasBodyNamed(ee, world.robot):
        return _Tracer(plant.GetBodyByName(ee, world.robot), np.zeros(3), arm=True)
    base = plant.get_body(plant.GetBodyIndices(world.robot)[0])
    return _Tracer(base, np.array([0.0, 0.0, 0.1]), arm=False)


def _set_camera(meshcat: Meshcat, views: list[_StepView], report) -> None:
    """A car's lot from the south and above (tree and samples in view); an arm from behind its shoulder,
    framing the robot, its path and the chosen object (every interpretation's object when nothing was reached)."""
    pts = [v.points(np.atleast_2d(v.start)) for v in views]
    focus = []  # the objects the arm goes for: the camera looks from their side
    for v in views:
        res = v.report.result
        if v.tracer.arm:  # the robot, its path and the object(s) it goes for; an arm's tree would zoom out too far
            if v.motion is not None:
                pts.append(v.points(v.motion))
            chosen = [res.goal_region.object] if res.goal_region is not None else \
                [o for i in report.grounding.interpretations for o in i.objects]
            focus.append(np.array([v.scene.object(o).pose.xyz for o in chosen], float).T.reshape(3, -1))
            pts.append(focus[-1])
            continue
        if res.tree is not None:
            pts.append(v.points(res.tree[0]))
        if res.goal_samples:
            pts.append(v.points(np.array([s.q for s in res.goal_samples])))
    p = np.concatenate(pts, axis=1)
    lo, hi = p.min(axis=1), p.max(axis=1)
    scene = views[0].scene
    if views[0].tracer.arm:
        base = scene.robot.base.pose() if scene.robot.base is not None else None
        p_WB = np.asarray(base.xyz if base else (0.0, 0.0, 0.0))
        lo, hi = np.minimum(lo, p_WB), np.maximum(hi, p_WB)  # include the robot's base
        yaw = base.rpy[2] if base else 0.0
        c, s = np.cos(yaw), np.sin(yaw)
        R_WB = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        # from behind the shoulder on the side where the work is, so the torso does not hide the arm
        side = 1.0 if (R_WB.T @ (focus[0].mean(axis=1) - p_WB))[1] >= 0 else -1.0
        direction = R_WB @ np.array([-0.8, side * 1.0, 1.0])
    else:
        direction = np.array([0.0, -0.7, 1.6])
    target = (lo + hi) / 2
    radius = max(float(np.linalg.norm(hi - lo)) / 2, 1.0 if views[0].tracer.arm else 0.6)  # an arm's own size
    camera = target + CAMERA_DISTANCE * radius * direction / np.linalg.norm(direction)
    meshcat.SetCameraPose(camera, target)


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", name)
