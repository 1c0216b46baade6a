"""Goal regions from per-type definitions (``lazyground/scene/types.yaml``): grasps, placements, parking.

``regions_for(obj, role, interpretation, scene)`` turns one scene object into
the goal regions of one role (``pick``, ``support``, ``park``). The numbers
live in ``types.yaml``; the templates below say what they mean.
"""

from __future__ import annotations

import difflib
import math

from grounding.grasps import GRASP_TEMPLATES, make_region
from grounding.lexicon import load_lexicon
from grounding.model import GroundingError
from lazyground.geometry import Pose
from lazyground.regions import ConfigRegion, GoalRegion, PlacementRegion
from lazyground.robots.end_effector import LEGACY_FRAME, EndEffectorSpec, end_effector_of
from lazyground.scene.schema import Scene, SceneObject
from lazyground.scene.types import type_definitions

DEG = math.pi / 180
END_EFFECTOR = LEGACY_FRAME  # the end effector when there is no scene


def check_types(scene: Scene, source: str | None = None) -> None:
    """Every object type must be defined (``types.yaml``) or declared by the scene (``grasp_types: {pillar: {}}``).

    A misspelt type would otherwise turn a goal into a plain obstacle without a word.

    Args:
        source: the file the message names (default: the scene's own; "" for none).

    Raises:
        GroundingError: the first undefined type, with the closest defined names.
    """
    known = type_definitions(scene)
    source = scene.source if source is None else source
    for i, obj in enumerate(scene.objects):
        if obj.type not in known:
            where = f"{source}: " if source else ""
            raise GroundingError(f"{where}objects[{i}].type: object {obj.id!r}: unknown type {obj.type!r}; "
                                 f"{_type_hint(obj.type, known)}(types: lazyground/scene/types.yaml; "
                                 f"a scene declares its own under grasp_types, e.g. 'grasp_types: {{{obj.type}: {{}}}}')")


def _type_hint(name: str, known) -> str:
    """"did you mean 'cup' (a 'mug' is one)? " for a misspelt type or a word naming one (the lexicon's nouns)."""
    nouns = {w.replace(" ", "_"): t for t, words in load_lexicon().data.get("nouns", {}).items() if t in known for w in words}
    nouns.update({t: t for t in known})
    close = difflib.get_close_matches(name.lower(), sorted(nouns), n=4, cutoff=0.6)
    first = {}  # type -> the closest word naming it
    for w in close:
        first.setdefault(nouns[w], w)
    said = [f"{t!r}" + (f" (a {w!r} is one)" if w != t else "") for t, w in list(first.items())[:2]]
    return f"did you mean {' or '.join(said)}? " if said else ""


def regions_for(obj: SceneObject, role: str, interpretation: str, scene: Scene | None = None) -> tuple[GoalRegion, ...]:
    """Goal regions for ``obj`` in ``role`` ("pick", "support" or "park").

    Raises:
        GroundingError: the type has no definition for that role.
    """
    definition = type_definitions(scene).get(obj.type, {}).get(role)
    if not definition:
        raise GroundingError(f"no {role} definition for type {obj.type!r} (see lazyground/scene/types.yaml)")
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
