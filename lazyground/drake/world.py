"""Scene → Drake: a RobotDiagram (plant + SceneGraph) and a collision-checker adapter.

With visualisation this is the only place pydrake is imported. At its edge
everything becomes numpy arrays over the *planned* coordinates.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Cylinder, Sphere
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.plant import CoulombFriction
from pydrake.multibody.tree import PlanarJoint, RevoluteJoint
from pydrake.planning import LinearDistanceAndInterpolationProvider, RobotDiagramBuilder, SceneGraphCollisionChecker

from lazyground.drake.robot_model import add_robot, allow_collisions
from lazyground.geometry import Pose
from lazyground.planning.space import ConfigSpace
from lazyground.robots.srdf import read_srdf
from lazyground.scene.schema import Geometry, Scene, SceneObject
from lazyground.scene.typed_yaml import SceneError

logging.getLogger("drake").setLevel(logging.WARNING)  # silence "Allocating contexts ..." INFO lines

PARKED_CAR_SIZE = (4.5, 1.8, 1.5)
OBSTACLE_RGBA = (0.8, 0.25, 0.2, 1.0)
OBJECT_RGBA = {
    "red": (0.85, 0.1, 0.1, 1.0), "green": (0.1, 0.7, 0.2, 1.0), "blue": (0.15, 0.3, 0.9, 1.0),
    "yellow": (0.95, 0.85, 0.1, 1.0), "white": (0.95, 0.95, 0.95, 1.0), "black": (0.1, 0.1, 0.1, 1.0),
    "orange": (1.0, 0.55, 0.0, 1.0), "brown": (0.55, 0.35, 0.2, 1.0), "grey": (0.6, 0.6, 0.6, 1.0),
    "gray": (0.6, 0.6, 0.6, 1.0), "purple": (0.55, 0.2, 0.75, 1.0),
}
TYPE_RGBA = {"table": (0.6, 0.45, 0.3, 1.0), "shelf": (0.55, 0.55, 0.6, 1.0), "parking_spot": (0.2, 0.8, 0.3, 0.35)}


def drake_shape(g: Geometry):
    if g.box:
        return Box(*g.box)
    if g.cylinder:
        return Cylinder(g.cylinder.radius, g.cylinder.length)
    return Sphere(g.sphere.radius)


def rigid_transform(pose: Pose) -> RigidTransform:
    return RigidTransform(RollPitchYaw(*pose.rpy), np.asarray(pose.xyz, float))


def object_rgba(obj: SceneObject) -> tuple:
    if obj.color and obj.color.lower() in OBJECT_RGBA:
        return OBJECT_RGBA[obj.color.lower()]
    return TYPE_RGBA.get(obj.type, (0.3, 0.6, 0.9, 1.0))


@dataclass(frozen=True)
class Attachment:
    """An object carried by a robot body: its geometry rides along at X_BO."""

    object: SceneObject
    body: str
    X_BO: Pose


class DrakeWorld:
    """The scene in Drake, with config checks over the planned coordinates.

    Args:
        scene: the loaded scene.
        padding: collision padding in metres (default: the scene's planner setting).
        attached: an object carried by the robot (removed from the environment).
        visual: also register visual geometry (for Meshcat).
        extend_builder: called with the RobotDiagramBuilder just before Build()
            (e.g. to add a MeshcatVisualizer to the diagram).

    Raises:
        SceneError: when the model cannot be parsed or the start is invalid for it.
    """

    def __init__(self, scene: Scene, padding: float | None = None, attached: Attachment | None = None, visual: bool = True, extend_builder=None):
        self.scene = scene
        self.attached = attached
        self.padding = scene.planner.collision_padding if padding is None else padding
        builder = RobotDiagramBuilder(time_step=0.0)
        plant = builder.plant()
        # package:// URIs, STL/DAE meshes: lazyground/drake/robot_model.py
        self.robot, self.model_files = add_robot(builder.parser(), scene.robot.model, scene.robot.packages, f"{scene.source}: robot.model")
        if scene.robot.base is not None:
            try:
                base = plant.GetFrameByName(scene.robot.base_link, self.robot)
            except Exception:
                raise SceneError(f"{scene.source}: robot.base_link: no link {scene.robot.base_link!r} in the model") from None
            try:
                plant.WeldFrames(plant.world_frame(), base, rigid_transform(scene.robot.base.pose()))
            except RuntimeError:  # e.g. the link already hangs on a joint to the world (a planar car)
                raise SceneError(f"{scene.source}: robot.base: cannot weld {scene.robot.base_link!r} to the world: it is already jointed to it") from None
        self._add_environment(plant, visual)
        if attached is not None:
            self._attach(plant, attached, visual)
        if extend_builder is not None:
            extend_builder(builder)
        diagram = builder.Build()
        self._setup_coordinates(diagram.plant())
        # Drake's edge checks step in the same weighted metric as ours (fixed coordinates weigh 0).
        weights = np.zeros(diagram.plant().num_positions())
        weights[self.planned] = self.space.weights
        self.checker = SceneGraphCollisionChecker(
            model=diagram,
            robot_model_instances=[self.robot],
            distance_and_interpolation_provider=LinearDistanceAndInterpolationProvider(diagram.plant(), weights),
            edge_step_size=0.05,
            env_collision_padding=self.padding,
            self_collision_padding=self.padding,
        )
        self.plant = self.checker.plant()
        self.diagram = self.checker.model()
        self._allow_collisions(scene.robot)
        self._check_time = 0.0
        self.checks = 0

    # --- building --------------------------------------------------------------------------
    def _allow_collisions(self, robot) -> None:
        """Link pairs never checked: the SRDF's disable_collisions (links it names that this model
        lacks are skipped: SRDFs often cover variants) and the scene's allowed_collisions."""
        if robot.srdf:
            allow_collisions(self.checker, self.plant, self.robot, read_srdf(robot.srdf).disabled_collisions, robot.srdf, strict=False)
        allow_collisions(self.checker, self.plant, self.robot, robot.allowed_collisions, f"{self.scene.source}: robot.allowed_collisions")

    def _add_environment(self, plant, visual: bool) -> None:
        world = plant.world_body()
        items = [(o.id, o.geometry, o.pose.pose(), OBSTACLE_RGBA) for o in self.scene.obstacles]
        carried = self.attached.object.id if self.attached else None
        for obj in self.scene.objects:
            if obj.type == "parking_spot" and obj.occupied:
                # no "/" in geometry names: Meshcat would nest the car under the spot's transform
                items.append((f"{obj.id}.parked_car", Geometry(box=PARKED_CAR_SIZE), _on_ground(obj), (0.75, 0.2, 0.2, 1.0)))
            elif obj.collides and obj.id != carried:
                items.append((obj.id, obj.geometry, obj.pose.pose(), object_rgba(obj)))
        for name, geometry, pose, rgba in items:
            X = rigid_transform(pose)
            shape = drake_shape(geometry)
            plant.RegisterCollisionGeometry(world, X, shape, name, _friction())
            if visual:
                plant.RegisterVisualGeometry(world, X, shape, name, np.array(rgba))
        if visual:  # non-colliding objects (parking spots) are still drawn
            for obj in self.scene.objects:
                if not obj.collides:
                    plant.RegisterVisualGeometry(world, rigid_transform(obj.pose.pose()), drake_shape(_flat_geometry(obj)), obj.id, np.array(object_rgba(obj)))

    def _attach(self, plant, attached: Attachment, visual: bool) -> None:
        body = plant.GetBodyByName(attached.body, self.robot)
        X = rigid_transform(attached.X_BO)
        shape = drake_shape(attached.object.geometry)
        name = f"carried/{attached.object.id}"
        plant.RegisterCollisionGeometry(body, X, shape, name, _friction())
        if visual:
            plant.RegisterVisualGeometry(body, X, shape, name, np.array(object_rgba(attached.object)))

    def _setup_coordinates(self, plant) -> None:
        robot = self.scene.robot
        names = plant.GetPositionNames(self.robot, add_model_instance_prefix=False, always_add_suffix=False)
        lower = plant.GetPositionLowerLimits()
        upper = plant.GetPositionUpperLimits()
        wrap = np.zeros(plant.num_positions(), bool)
        joint_of = [""] * plant.num_positions()
        for ji in plant.GetJointIndices(self.robot):
            joint = plant.get_joint(ji)
            for k in range(joint.num_positions()):
                joint_of[joint.position_start() + k] = joint.name()
            if isinstance(joint, PlanarJoint):
                wrap[joint.position_start() + 2] = True
            elif isinstance(joint, RevoluteJoint) and not np.isfinite(joint.position_upper_limits()[0]):
                wrap[joint.position_start()] = True
        all_names = list(names)
        planned = robot.planned_joints
        if planned is not None:
            unknown = [j for j in planned if j not in joint_of and j not in all_names]
            if unknown:
                raise SceneError(f"{self.scene.source}: robot.planned_joints: no joint {unknown[0]!r} in the model (joints: {', '.join(dict.fromkeys(joint_of))})")
        self.planned = [i for i, n in enumerate(all_names) if planned is None or n in planned or joint_of[i] in planned]
        if not self.planned:
            raise SceneError(f"{self.scene.source}: robot: nothing to plan: no movable joint selected (robot.planned_joints)")
        for key in list(robot.start) + list(robot.limits) + list(robot.weights):
            if key not in all_names:
                raise SceneError(f"{self.scene.source}: robot: no position {key!r} in the model (positions: {', '.join(all_names)})")
        lower, upper = lower.copy(), upper.copy()
        for key, (lo, hi) in robot.limits.items():
            i = all_names.index(key)
            lower[i], upper[i] = lo, hi
        self.q_full = np.zeros(plant.num_positions())
        for key, v in robot.start.items():
            self.q_full[all_names.index(key)] = v
        for i in range(len(all_names)):
            v = self.q_full[i]
            if not wrap[i] and not lower[i] - 1e-9 <= v <= upper[i] + 1e-9:
                raise SceneError(f"{self.scene.source}: robot.start.{all_names[i]}: {v:g} is outside the joint limits [{lower[i]:g}, {upper[i]:g}]")
        idx = self.planned
        for i in idx:
            if not wrap[i] and not (np.isfinite(lower[i]) and np.isfinite(upper[i])):
                raise SceneError(f"{self.scene.source}: robot.limits: position {all_names[i]!r} is unbounded; give its limits")
        weights = np.array([robot.weights.get(all_names[i], 1.0) for i in idx])
        self.space = ConfigSpace(tuple(all_names[i] for i in idx), lower[idx], upper[idx], weights, wrap[idx])
        self.start = self.q_full[idx].copy()
        self._plans_all = idx == list(range(len(all_names)))

    # --- kinematics ------------------------------------------------------------------------
    def frame_pose(self, frame: str, q: np.ndarray) -> Pose:
        """World pose X_WF of a robot frame at planned coordinates ``q``."""
        if not hasattr(self, "_fk_context"):
            self._fk_context = self.plant.CreateDefaultContext()
        self.plant.SetPositions(self._fk_context, self.full(q))
        X = self.plant.CalcRelativeTransform(self._fk_context, self.plant.world_frame(), self.plant.GetFrameByName(frame, self.robot))
        return Pose.from_matrix(X.GetAsMatrix4())

    # --- ValidityChecker -------------------------------------------------------------------
    @property
    def check_time(self) -> float:
        return self._check_time

    def full(self, q: np.ndarray) -> np.ndarray:
        """The plant's position vector for planned coordinates ``q`` (rows or one vector)."""
        q = np.asarray(q, float)
        if self._plans_all:
            return q
        out = np.empty(q.shape[:-1] + self.q_full.shape)
        out[...] = self.q_full
        out[..., self.planned] = q
        return out

    def config_free(self, q: np.ndarray) -> bool:
        t0 = time.perf_counter()
        free = self.checker.CheckConfigCollisionFree(self.full(q))
        self._check_time += time.perf_counter() - t0
        self.checks += 1
        return bool(free)

    def configs_free(self, qs: np.ndarray) -> np.ndarray:
        qs = np.atleast_2d(qs)
        if len(qs) == 1:
            return np.array([self.config_free(qs[0])])
        t0 = time.perf_counter()
        full = self.full(qs)
        free = self.checker.CheckConfigsCollisionFree(list(full), parallelize=False)
        self._check_time += time.perf_counter() - t0
        self.checks += len(qs)
        return np.asarray(free, bool)

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the motion a → b is free, checked in C++ every ``resolution`` with early exit.

        Drake interpolates linearly, so b is first unwrapped onto the shorter arc
        from a (an angle of 3.5 rad is the same pose as -2.78 rad). Drake's
        weighted metric counts an angle step w·|dθ|, never less than our chord,
        so its steps are at least as fine as ``resolution`` in our metric.
        """
        return bool(self._edge(self.checker.CheckEdgeCollisionFree, a, b, resolution))

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The largest t in [0, 1] with a → a + t (b - a) free at ``resolution`` (1: all free; 0: blocked at once).

        Drake's ``MeasureEdgeCollisionFree``: the last free check before the first
        collision, as OMPL's ``checkMotion(s1, s2, lastValid)``.
        """
        measure = self._edge(self.checker.MeasureEdgeCollisionFree, a, b, resolution)
        return max(0.0, measure.alpha_or(0.0))

    def _edge(self, check, a, b, resolution: float):
        if self.checker.edge_step_size() != resolution:
            self.checker.set_edge_step_size(resolution)
        t0 = time.perf_counter()
        a = np.asarray(a, float)
        out = check(self.full(a), self.full(a + self.space.difference(a, b)))
        self._check_time += time.perf_counter() - t0
        self.checks += 1
        return out

    def explain(self, q: np.ndarray) -> str:
        """The colliding pairs at q, e.g. "car_body collides with wall_1"."""
        pairs = self.colliding_pairs(q)
        if not pairs:
            return "no colliding pair found"
        shown = ", ".join(f"{a} collides with {b}" for a, b in pairs[:3])
        return shown + (f" (+{len(pairs) - 3} more)" if len(pairs) > 3 else "")

    def colliding_pairs(self, q: np.ndarray) -> list[tuple[str, str]]:
        self.checker.UpdatePositions(self.full(q))
        sg = self.diagram.scene_graph()
        sg_ctx = sg.GetMyContextFromRoot(self.checker.model_context().model_context())
        query = sg.get_query_output_port().Eval(sg_ctx)
        inspector = query.inspector()
        pairs = []
        for p in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=self.padding + 1e-9):
            if p.distance > self.padding:
                continue
            pairs.append((self._geometry_name(inspector, p.id_A), self._geometry_name(inspector, p.id_B)))
        return sorted(set(pairs))

    def _geometry_name(self, inspector, gid) -> str:
        body = self.plant.GetBodyFromFrameId(inspector.GetFrameId(gid))
        if body is None or body.index() == self.plant.world_body().index():
            return inspector.GetName(gid).split("::")[-1]
        return body.name()


def _friction() -> CoulombFriction:
    return CoulombFriction(0.5, 0.5)


def _on_ground(obj: SceneObject) -> Pose:
    x, y, _ = obj.pose.xyz
    return Pose((x, y, PARKED_CAR_SIZE[2] / 2), (0.0, 0.0, obj.pose.rpy[2]))


def _flat_geometry(obj: SceneObject) -> Geometry:
    """Non-colliding markers (parking spots) are drawn as thin slabs on their pose."""
    if obj.geometry.box:
        x, y, _ = obj.geometry.box
        return Geometry(box=(x, y, 0.01))
    return obj.geometry
