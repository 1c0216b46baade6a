"""Scene → Drake diagram: the robot model, the environment's geometry and a carried object.

Only geometry is decided here; colours come from :mod:`lazyground.scene.colours`
and what an occupied parking spot holds from the object types
(:func:`lazyground.scene.types.occupant_geometry`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from pydrake.geometry import Box, Cylinder, Sphere
from pydrake.multibody.plant import CoulombFriction
from pydrake.planning import RobotDiagramBuilder

from lazyground.drake.robot_model import add_scene_robot, rigid_transform
from lazyground.geometry import Pose
from lazyground.scene.colours import OCCUPANT_RGBA, object_rgba, obstacle_rgba
from lazyground.scene.schema import Geometry, Scene, SceneObject
from lazyground.scene.types import occupant_geometry
from lazyground.typed_yaml import SceneError


@dataclass(frozen=True)
class Attachment:
    """An object carried by a robot body: its geometry rides along at X_BO."""

    object: SceneObject
    body: str
    X_BO: Pose


def drake_shape(g: Geometry):
    """The Drake shape of a scene geometry."""
    if g.mesh:  # #15: imported MoveIt meshes (OBJ, or STL converted in memory)
        from lazyground.drake.mesh_shape import mesh_shape

        return mesh_shape(g.mesh)
    if g.box:
        return Box(*g.box)
    if g.cylinder:
        return Cylinder(g.cylinder.radius, g.cylinder.length)
    return Sphere(g.sphere.radius)


def build_diagram(scene: Scene, attached: Attachment | None = None, visual: bool = True, extend_builder=None,
                  notes: list | None = None, mimic: list | None = None):
    """The scene's RobotDiagram and the robot's model instance.

    Args:
        scene: the loaded scene.
        attached: an object carried by the robot (removed from the environment).
        visual: also register visual geometry (for Meshcat).
        extend_builder: called with the RobotDiagramBuilder just before Build().
        notes: gains what was done to the model that the scene did not say (a floating base
            welded, continuous limits dropped, visuals drawn from collision geometry).
        mimic: gains the model's mimic joints (lazyground.robots.tools.Mimic).

    Returns:
        (diagram, robot): the built RobotDiagram and the robot's ModelInstanceIndex.

    Raises:
        SceneError: the model cannot be parsed or its base cannot be welded as the scene says.
    """
    builder = RobotDiagramBuilder(time_step=0.0)
    plant = builder.plant()
    robot, model_notes, model_mimic = add_scene_robot(builder, scene, visual)  # xacro, package://, meshes, tools, base, SRDF
    if notes is not None:
        notes.extend(model_notes)
    if mimic is not None:
        mimic.extend(model_mimic)
    _add_environment(plant, scene, attached, visual)
    if attached is not None:
        _attach(plant, robot, attached, visual)
    if extend_builder is not None:
        extend_builder(builder)
    return builder.Build(), robot


def environment_items(scene: Scene, attached: Attachment | None = None) -> list[tuple[str, Geometry, Pose, tuple]]:
    """(name, geometry, pose, rgba) of every colliding environment body."""
    items = [(o.id, o.geometry, o.pose.pose(), obstacle_rgba(o)) for o in scene.obstacles]
    carried = attached.object.id if attached else None
    for obj in scene.objects:
        occupant = occupant_geometry(obj, scene) if obj.occupied else None
        if occupant is not None:
            # no "/" in geometry names: Meshcat would nest the occupant under the spot's transform
            items.append((f"{obj.id}.parked_car", occupant, on_ground(obj, occupant), OCCUPANT_RGBA))
        elif obj.collides and obj.id != carried:
            items.append((obj.id, obj.geometry, obj.pose.pose(), object_rgba(obj)))
    return items


def on_ground(obj: SceneObject, occupant: Geometry) -> Pose:
    """The pose of what occupies ``obj``: resting on the ground at its x, y and heading."""
    x, y, _ = obj.pose.xyz
    return Pose((x, y, occupant.half_extents()[2]), (0.0, 0.0, obj.pose.rpy[2]))


def _add_environment(plant, scene: Scene, attached: Attachment | None, visual: bool) -> None:
    world = plant.world_body()
    for name, geometry, pose, rgba in environment_items(scene, attached):
        X = rigid_transform(pose)
        shape = drake_shape(geometry)
        try:
            plant.RegisterCollisionGeometry(world, X, shape, name, _friction())
        except RuntimeError as exc:  # a mesh file with no vertices Drake can read (not an OBJ) has no convex hull
            raise SceneError(f"{scene.source}: {name}: cannot use its geometry: {str(exc).splitlines()[0]}") from None
        if visual:
            plant.RegisterVisualGeometry(world, X, shape, name, np.array(rgba))
    if visual:  # non-colliding objects (parking spots) are still drawn
        for obj in scene.objects:
            if not obj.collides:
                plant.RegisterVisualGeometry(world, rigid_transform(obj.pose.pose()), drake_shape(_flat_geometry(obj)), obj.id, np.array(object_rgba(obj)))


def _attach(plant, robot, attached: Attachment, visual: bool) -> None:
    body = plant.GetBodyByName(attached.body, robot)
    X = rigid_transform(attached.X_BO)
    shape = drake_shape(attached.object.geometry)
    name = f"carried/{attached.object.id}"
    plant.RegisterCollisionGeometry(body, X, shape, name, _friction())
    if visual:
        plant.RegisterVisualGeometry(body, X, shape, name, np.array(object_rgba(attached.object)))


def _friction() -> CoulombFriction:
    return CoulombFriction(0.5, 0.5)


def _flat_geometry(obj: SceneObject) -> Geometry:
    """Non-colliding markers (parking spots) are drawn as thin slabs on their pose."""
    if obj.geometry.box:
        x, y, _ = obj.geometry.box
        return Geometry(box=(x, y, 0.01))
    return obj.geometry
