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

from pydrake.geometry import CollisionFilterDeclaration, GeometrySet
from pydrake.multibody.parsing import Parser

from lazyground.robots.description import PreparedModel, prepare_model
from lazyground.robots.srdf import read_srdf
from lazyground.typed_yaml import SceneError


def add_robot(parser: Parser, model: str | Path, packages: dict[str, Path] | None = None, where: str = "robot.model"):
    """Parse the robot model into the parser's plant.

    Args:
        parser: a Drake parser (its package map gains every package the model used).
        model: the URDF or SDF file.
        packages: package folders by name (scene ``robot.packages``, ``--package``).
        where: what to name in an error (e.g. ``scene.yaml: robot.model``).
    Returns:
        (model instance, the PreparedModel: meshes resolved and converted).
    Raises:
        SceneError: one line, naming the file and what to do.
    """
    prepared: PreparedModel = prepare_model(model, packages)
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


def add_scene_robot(builder, scene):
    """A scene's robot: parsed (packages, meshes) with its SRDF pairs and allowed collisions filtered.

    Raises:
        SceneError: the model cannot be loaded, or ``allowed_collisions`` names an unknown link.
    """
    robot, _ = add_robot(builder.parser(), scene.robot.model, scene.robot.packages, f"{scene.source}: robot.model")
    plant, scene_graph = builder.plant(), builder.scene_graph()
    if scene.robot.srdf:
        allow_collisions(scene_graph, plant, robot, read_srdf(scene.robot.srdf).disabled_collisions, scene.robot.srdf, strict=False)
    allow_collisions(scene_graph, plant, robot, scene.robot.allowed_collisions, f"{scene.source}: robot.allowed_collisions")
    return robot
