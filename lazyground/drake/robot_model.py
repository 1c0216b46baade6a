"""Loading a robot description into a plant, and filtering the link pairs it allows.

``add_robot`` parses a URDF/SDF through ``lazyground.robots.description.prepare_model``
(``package://`` resolution, STL/DAE meshes converted to OBJ), so a ROS description package
loads without edits. ``allow_collisions`` filters link pairs in a collision checker: an
SRDF's ``disable_collisions`` and a scene's ``robot.allowed_collisions``.
"""

from __future__ import annotations

from pathlib import Path

from pydrake.multibody.parsing import Parser

from lazyground.robots.description import PreparedModel, prepare_model
from lazyground.scene.typed_yaml import SceneError


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


def allow_collisions(checker, plant, robot, pairs, where: str, strict: bool = True) -> list[tuple[str, str]]:
    """Stop checking each (link_a, link_b) pair against each other.

    Args:
        checker: a SceneGraphCollisionChecker over ``plant``.
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
    for a, b in pairs:
        missing = [n for n in (a, b) if not plant.HasBodyNamed(n, robot)]
        if missing:
            if strict:
                raise SceneError(f"{where}: no link {missing[0]!r} in the robot model (pair {a}, {b})")
            skipped.append((a, b))
            continue
        if a != b:
            checker.SetCollisionFilteredBetween(plant.GetBodyByName(a, robot), plant.GetBodyByName(b, robot), True)
    return skipped
