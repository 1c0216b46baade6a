"""Goal regions from per-type definitions (``lazyground/scene/types.yaml``): grasps, placements, parking.

``regions_for(obj, role, interpretation, scene)`` turns one scene object into
the goal regions of one role (``pick``, ``support``, ``park``). The numbers
live in ``types.yaml``; the templates below say what they mean.
"""

from __future__ import annotations

import difflib
import math
from pathlib import Path

from grounding.grasps import GRASP_TEMPLATES, make_region
from grounding.model import GroundingError
from lazyground.geometry import Pose
from lazyground.regions import ConfigRegion, GoalRegion, PlacementRegion
from lazyground.robots.end_effector import LEGACY_FRAME, EndEffectorSpec, end_effector_of
from lazyground.scene.schema import Scene, SceneObject
from lazyground.typed_yaml import line_of
from lazyground.scene.types import type_definitions

DEG = math.pi / 180
END_EFFECTOR = LEGACY_FRAME  # the end effector when there is no scene


def check_types(scene: Scene) -> None:
    """Every object type must be defined (``types.yaml``) or declared by the scene (``grasp_types: {pillar: {}}``).

    A misspelt type would otherwise turn a goal into a plain obstacle without a word.

    Raises:
        GroundingError: the first undefined type, with the closest defined names.
    """
    known = type_definitions(scene)
    for i, obj in enumerate(scene.objects):
        if obj.type not in known:
            close = difflib.get_close_matches(obj.type, sorted(known), n=2, cutoff=0.6) or _by_synonym(obj.type, known)
            hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
            raise GroundingError(f"object {obj.id!r}: unknown type {obj.type!r}; {hint}(types: lazyground/scene/types.yaml; "
                                 f"a scene declares its own under grasp_types, e.g. 'grasp_types: {{{obj.type}: {{}}}}')"
                                 f"{_where(scene, f'objects[{i}].type')}")


def _by_synonym(type_name: str, known: dict) -> list[str]:
    """Types whose lexicon words are close to a misspelt type ("mugg" -> "mug", a word for cup)."""
    from grounding.lexicon import load_lexicon  # the word table, read once

    words = {str(w).lower(): t for t, ws in (load_lexicon().data.get("nouns") or {}).items() for w in ws or [] if t in known}
    close = difflib.get_close_matches(type_name.lower().replace("_", " "), sorted(words), n=2, cutoff=0.7)
    return list(dict.fromkeys(words[w] for w in close))


def _where(scene: Scene, path: str) -> str:
    """" (scene.yaml line 12)" for a key of the scene's file, "" when the file cannot be read."""
    try:
        line = line_of(Path(scene.source).read_text(), path) if scene.source else None
    except (OSError, UnicodeDecodeError):
        line = None
    return f" ({scene.source} line {line})" if line else ""


def regions_for(obj: SceneObject, role: str, interpretation: str, scene: Scene | None = None,
                ee: EndEffectorSpec | None = None) -> tuple[GoalRegion, ...]:
    """Goal regions for ``obj`` in ``role`` ("pick", "support" or "park").

    ``ee``: the scene robot's end effector when the caller has it already (it is read from the robot's files).

    Raises:
        GroundingError: the type has no definition for that role.
    """
    definition = type_definitions(scene).get(obj.type, {}).get(role)
    if not definition:
        raise GroundingError(f"no {role} definition for type {obj.type!r} (see lazyground/scene/types.yaml)")
    if ee is None:
        ee = end_effector_of(scene.robot) if scene is not None else EndEffectorSpec(frame=END_EFFECTOR)
    out: list[GoalRegion] = []
    try:
        for spec in definition:
            template = TEMPLATES.get(spec.get("template"))
            if template is None:
                raise GroundingError(f"type {obj.type!r}: unknown region template {spec.get('template')!r}")
            out.extend(template(obj, spec, interpretation, ee))
    except GroundingError:
        raise
    except (AttributeError, KeyError, TypeError, ValueError) as exc:  # a scene's grasp_types override is malformed
        raise GroundingError(f"type {obj.type!r}: malformed {role} definition ({type(exc).__name__}: {exc})") from None
    return tuple(out)


def surface(obj, spec, interpretation, ee):
    """Placement on the top surface: the carried object's base frame over the free area."""
    hx, hy, hz = obj.geometry.half_extents()
    m = spec["margin"]
    X_WR = obj.pose.pose().compose(Pose((0.0, 0.0, hz), (0.0, 0.0, 0.0)))
    c = spec["clearance"]
    # the carried object comes straight down from ``approach`` above
    return [make_region(PlacementRegion, obj, interpretation, "surface", (-(hx - m), -(hy - m), c, 0, 0, -math.pi), (hx - m, hy - m, c, 0, 0, math.pi),
                        X_WR=X_WR, approach=(0.0, 0.0, float(spec.get("approach", 0.0))))]


def parking(obj, spec, interpretation, ee):
    """(x, y, heading) boxes: forwards into the spot and reversing in."""
    x, y, _ = obj.pose.xyz
    yaw = obj.pose.rpy[2]
    tol, htol = spec["position_tolerance"], spec["heading_tolerance"] * DEG
    out = []
    for label, heading in (("forwards", yaw), ("reversing", yaw + math.pi)):
        lo_h = math.remainder(heading - htol, 2 * math.pi)
        hi_h = math.remainder(heading + htol, 2 * math.pi)
        out.append(make_region(ConfigRegion, obj, interpretation, label, (x - tol, y - tol, lo_h), (x + tol, y + tol, hi_h), wrap=(2,)))
    return out


TEMPLATES = {**GRASP_TEMPLATES, "surface": surface, "parking": parking}
