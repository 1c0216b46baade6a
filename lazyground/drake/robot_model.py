"""Loading a robot description into a plant, and filtering the link pairs it allows.

``add_robot`` parses a URDF/SDF through ``lazyground.robots.description.prepare_model``
(``package://`` resolution, STL/DAE meshes converted to OBJ), so a ROS description package
loads without edits. ``allow_collisions`` excludes link pairs in the SceneGraph before the
diagram is built (so every collision checker over it agrees): an SRDF's
``disable_collisions`` and a scene's ``robot.allowed_collisions``. ``add_scene_robot`` does
both for a scene's robot.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.math import RigidTransform, RollPitchYaw
from pydrake.multibody.parsing import Parser

from lazyground.robots.description import PreparedModel, prepare_model
from lazyground.robots.srdf import read_srdf
from lazyground.robots.tools import mimic_joints, mount_tools
from lazyground.typed_yaml import SceneError


def add_robot(parser: Parser, model: str | Path, packages: dict[str, Path] | None = None, where: str = "robot.model",
              xacro_args: dict | None = None, visual: bool = True, base_link: str | None = None, tools=()):
    """Parse the robot model into the parser's plant.

    Args:
        parser: a Drake parser (its package map gains every package the model used).
        model: the URDF, SDF or xacro file.
        packages: package folders by name (scene ``robot.packages``, ``--package``).
        where: what to name in an error (e.g. ``scene.yaml: robot.model``).
        xacro_args: ``arg`` values of a xacro file.
        visual: also load visual geometry (a viewer); planning needs collision geometry only.
        base_link: the link a scene's ``robot.base`` welds (the model's own weld of it to ``world`` is dropped).
        tools: ``ToolSpec``s mounted on the model before Drake parses it (lazyground/robots/tools.py).
    Returns:
        (model instance, the PreparedModel: meshes resolved and converted).
    Raises:
        SceneError: one line, naming the file and what to do.
    """
    try:
        prepared: PreparedModel = prepare_model(model, packages, xacro_args=xacro_args, visual=visual, base_link=base_link)
    except SceneError as exc:
        raise SceneError(f"{where}: {exc}") from None
    mounted = []
    for i, tool in enumerate(tools):
        try:
            mounted.append((prepare_model(tool.model, packages, xacro_args=tool.xacro_args, visual=visual), tool.parent,
                            tool.pose.xyz, tool.pose.rpy))
        except SceneError as exc:
            raise SceneError(f"{where.rsplit(':', 1)[0]}: robot.tools[{i}].model: {exc}") from None
    prepared = mount_tools(prepared, mounted, f"{where.rsplit(':', 1)[0]}: robot.tools")
    for name, folder in prepared.packages.items():
        if not parser.package_map().Contains(name):
            parser.package_map().Add(name, folder)
    try:
        instances = parser.AddModelsFromString(prepared.text, prepared.file_type)
    except Exception as exc:  # Drake's parser raises RuntimeError with multi-line text
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
        raise SceneError(f"{where}: cannot parse {model}: {first}") from None
    if len(instances) != 1:
        raise SceneError(f"{where}: {model} holds {len(instances)} models; a robot file must hold one")
    return instances[0], prepared


def allow_collisions(scene_graph, plant, robot, pairs, where: str, strict: bool = True) -> list[tuple[str, str]]:
    """Stop checking each (link_a, link_b) pair against each other (before the diagram is built).

    Args:
        scene_graph: the builder's SceneGraph (its model-level filters).
        plant: the MultibodyPlant the robot was parsed into.
        robot: the robot's model instance.
        pairs: link-name pairs.
        where: what to name in an error (``robot.allowed_collisions``, the SRDF path).
        strict: an unknown link is an error (a scene's list) or skipped (an SRDF often names
            links of another variant of the robot).
    Returns:
        The pairs skipped because a link is not in the model.
    Raises:
        SceneError: with ``strict``, a link the model does not have.
    """
    skipped = []
    manager = scene_graph.collision_filter_manager()
    for a, b in pairs:
        missing = [n for n in (a, b) if not plant.HasBodyNamed(n, robot)]
        if missing:
            if strict:
                raise SceneError(f"{where}: no link {missing[0]!r} in the robot model (pair {a}, {b})")
            skipped.append((a, b))
            continue
        frames = [plant.GetBodyFrameIdOrThrow(plant.GetBodyByName(n, robot).index()) for n in (a, b)]
        manager.Apply(CollisionFilterDeclaration().ExcludeBetween(GeometrySet(frames[0]), GeometrySet(frames[1])))
    return skipped


def add_scene_robot(builder, scene, visual: bool = True):
    """A scene's robot: parsed (packages, meshes), its base welded, its SRDF pairs and allowed collisions filtered.

    Returns:
        (model instance, notes: what was done that the scene did not say, the model's mimic joints).
    Raises:
        SceneError: the model cannot be loaded or welded, or ``allowed_collisions`` names an unknown link.
    """
    robot, prepared = add_robot(builder.parser(), scene.robot.model, scene.robot.packages, f"{scene.source}: robot.model",
                                scene.robot.xacro_args, visual, scene.robot.base_link if scene.robot.base is not None else None,
                                scene.robot.tools)
    plant, scene_graph = builder.plant(), builder.scene_graph()
    pose = rigid_transform(scene.robot.base.pose()) if scene.robot.base is not None else None
    note = weld_base(plant, robot, scene.robot.base_link, pose, f"{scene.source}: robot.base")
    if scene.robot.srdf:
        allow_collisions(scene_graph, plant, robot, read_srdf(scene.robot.srdf).disabled_collisions, scene.robot.srdf, strict=False)
    allow_collisions(scene_graph, plant, robot, scene.robot.allowed_collisions, f"{scene.source}: robot.allowed_collisions")
    return robot, prepared.notes + ((note,) if note else ()), mimic_joints(prepared.text, prepared.file_type)


def rigid_transform(pose) -> RigidTransform:
    """A scene pose as a Drake RigidTransform."""
    return RigidTransform(RollPitchYaw(*pose.rpy), np.asarray(pose.xyz, float))


def root_bodies(plant, robot) -> list[str]:
    """The robot's bodies no joint moves relative to a parent (before Finalize): each floats unless welded."""
    children = {plant.get_joint(j).child_body().index() for j in plant.GetJointIndices(robot)}
    return [plant.get_body(b).name() for b in plant.GetBodyIndices(robot) if b not in children]


def floating_link(plant, robot, base_link: str | None) -> str | None:
    """The link :func:`weld_base` welds at the origin when no pose is given: ``base_link`` if it floats, else the first
    floating root; None when the model joints itself to the world."""
    roots = root_bodies(plant, robot)
    return (base_link if base_link in roots else roots[0]) if roots else None


def weld_base(plant, robot, base_link: str | None, X_WB=None, where: str = "robot.base") -> str | None:
    """Weld the robot's base to the world as planning does; one note when the model floated and no pose was given.

    With a pose (``robot.base``), ``base_link`` is welded there. Without, a model already
    jointed to the world is left as it is; a floating one is welded at the origin by its
    ``base_link`` when that is a root, else by its first root body.

    Returns:
        The note (None when the scene said where, or nothing floated).
    Raises:
        SceneError: ``base_link`` is not in the model, or it is already jointed to the world.
    """
    if X_WB is not None:
        if not plant.HasBodyNamed(base_link, robot):
            raise SceneError(f"{where}: no link {base_link!r} in the model (robot.base_link)")
        try:
            plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(base_link, robot), X_WB)
        except RuntimeError:  # e.g. the link already hangs on a joint to the world (a planar car)
            raise SceneError(f"{where}: cannot weld {base_link!r} to the world: it is already jointed to it") from None
        return None
    link = floating_link(plant, robot, base_link)
    if link is None:
        return None
    plant.WeldFrames(plant.world_frame(), plant.GetFrameByName(link, robot), RigidTransform())
    return (f"the model is not welded to the world: {link} welded at the origin "
            f"(give robot.base: {{xyz: [x, y, z]}} to place it)")
