"""Goal regions from per-type definitions (``types.yaml``): grasps, placements, parking.

``regions_for(obj, role, interpretation, scene)`` turns one scene object into
the goal regions of one role (``pick``, ``support``, ``park``). The numbers
live in ``types.yaml``; the templates below say what they mean.
"""

from __future__ import annotations

import difflib
import math
from functools import lru_cache
from pathlib import Path

import yaml

from grounding.model import GroundingError
from lazyground.geometry import Pose
from lazyground.regions import ConfigRegion, GoalRegion, PlacementRegion, WorkspaceRegion
from lazyground.scene.schema import Geometry, Scene, SceneObject
from lazyground.scene.typed_yaml import SceneError, load_dataclass

TYPES_FILE = Path(__file__).with_name("types.yaml")
DEG = math.pi / 180
END_EFFECTOR = "gripper_link"


@lru_cache(maxsize=1)
def default_types() -> dict:
    return yaml.safe_load(TYPES_FILE.read_text())


def type_definitions(scene: Scene | None) -> dict:
    """The bundled definitions with the scene's ``grasp_types`` overrides applied per type."""
    types = dict(default_types())
    if scene is not None and scene.grasp_types:
        types.update(scene.grasp_types)
    return types


def occupant_geometry(obj: SceneObject, scene: Scene | None = None) -> Geometry | None:
    """What an occupied ``obj`` holds: its own ``occupant``, else its type's; None if neither says.

    Raises:
        GroundingError: the type's ``occupant`` entry is not a geometry.
    """
    if obj.occupant is not None:
        return obj.occupant
    spec = type_definitions(scene).get(obj.type, {}).get("occupant")
    if spec is None:
        return None
    try:
        return load_dataclass(spec, Geometry, f"{obj.type}.occupant")
    except SceneError as exc:
        raise GroundingError(f"grounding/types.yaml: {exc}") from None


def check_types(scene: Scene) -> None:
    """Every object type must be defined (``types.yaml``) or declared by the scene (``grasp_types: {pillar: {}}``).

    A misspelt type would otherwise turn a goal into a plain obstacle without a word.

    Raises:
        GroundingError: the first undefined type, with the closest defined names.
    """
    known = type_definitions(scene)
    for obj in scene.objects:
        if obj.type not in known:
            close = difflib.get_close_matches(obj.type, sorted(known), n=2, cutoff=0.6)
            hint = f"did you mean {' or '.join(repr(c) for c in close)}? " if close else ""
            raise GroundingError(f"object {obj.id!r}: unknown type {obj.type!r}; {hint}(types: grounding/types.yaml; "
                                 f"a scene declares its own under grasp_types, e.g. 'grasp_types: {{{obj.type}: {{}}}}')")


def regions_for(obj: SceneObject, role: str, interpretation: str, scene: Scene | None = None) -> tuple[GoalRegion, ...]:
    """Goal regions for ``obj`` in ``role`` ("pick", "support" or "park").

    Raises:
        GroundingError: the type has no definition for that role.
    """
    definition = type_definitions(scene).get(obj.type, {}).get(role)
    if not definition:
        raise GroundingError(f"no {role} definition for type {obj.type!r} (see grounding/types.yaml)")
    ee = (scene.robot.end_effector if scene is not None and scene.robot.end_effector else END_EFFECTOR)
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


def _top_z(obj: SceneObject) -> float:
    return obj.geometry.half_extents()[2]


def _approach(spec, axis: int, sign: float) -> tuple[float, float, float]:
    """The pre-pose offset from ``spec['approach']`` (metres) along one axis of the target frame."""
    v = [0.0, 0.0, 0.0]
    v[axis] = sign * float(spec.get("approach", 0.0))
    return tuple(v)


def _region(cls, obj, interpretation, label, lower, upper, **fields):
    """A region of class ``cls`` on ``obj``, named ``<object id>/<label>``."""
    return cls(
        id=f"{obj.id}/{label}",
        interpretation=interpretation,
        object=obj.id,
        lower=tuple(float(v) for v in lower),
        upper=tuple(float(v) for v in upper),
        label=label,
        **fields,
    )


def top(obj, spec, interpretation, ee):
    """Approach from above: R on the top face, R.x down; depth above the face, any yaw."""
    d0, d1 = spec["depth"]
    X_WR = obj.pose.pose().compose(Pose((0.0, 0.0, _top_z(obj)), (0.0, math.pi / 2, 0.0)))
    # R.x points down, so "above the face" is negative x in R.
    return [_region(WorkspaceRegion, obj, interpretation, "top", (-d1, 0, 0, -math.pi, 0, 0), (-d0, 0, 0, math.pi, 0, 0), frame=ee, X_WR=X_WR,
                    approach=_approach(spec, 0, -1.0))]


FACES = {"+x": (0, 1, math.pi), "-x": (0, -1, 0.0), "+y": (1, 1, -math.pi / 2), "-y": (1, -1, math.pi / 2)}


def side_faces(obj, spec, interpretation, ee):
    """One region per vertical face of a box: horizontal approach into the face."""
    hx, hy, hz = obj.geometry.half_extents()
    d0, d1 = spec["depth"]
    l0, l1 = spec["lateral"]
    h = max(0.0, hz - spec.get("height_margin", 0.0))
    out = []
    for name, (axis, sign, yaw) in FACES.items():
        offset = [0.0, 0.0, 0.0]
        offset[axis] = sign * (hx, hy)[axis]
        X_WR = obj.pose.pose().compose(Pose(tuple(offset), (0.0, 0.0, yaw)))
        out.append(_region(WorkspaceRegion, obj, interpretation, f"face {name}", (d0, l0, -h, 0, 0, 0), (d1, l1, h, 0, 0, 0), frame=ee, X_WR=X_WR,
                           approach=_approach(spec, 0, -1.0)))
    return out


def side_around(obj, spec, interpretation, ee):
    """A cylinder's side from any horizontal direction, over part of its height."""
    r, _, hz = obj.geometry.half_extents()
    f0, f1 = spec["height_fraction"]
    d0, d1 = spec["depth"]
    X_WR = obj.pose.pose()
    # sample: yaw about the axis, height; then back off along the approach axis by the radius
    X_SE = Pose((-(r - (d0 + d1) / 2), 0.0, 0.0), (0.0, 0.0, 0.0))
    lo_z, hi_z = -hz + 2 * hz * f0, -hz + 2 * hz * f1
    half_depth = (d1 - d0) / 2
    return [_region(WorkspaceRegion, obj, interpretation, "side", (-half_depth, 0, lo_z, 0, 0, -math.pi), (half_depth, 0, hi_z, 0, 0, math.pi), frame=ee, X_WR=X_WR, X_SE=X_SE,
                    approach=_approach(spec, 0, -1.0))]


def surface(obj, spec, interpretation, ee):
    """Placement on the top surface: the carried object's base frame over the free area."""
    hx, hy, hz = obj.geometry.half_extents()
    m = spec["margin"]
    X_WR = obj.pose.pose().compose(Pose((0.0, 0.0, hz), (0.0, 0.0, 0.0)))
    c = spec["clearance"]
    return [_region(PlacementRegion, obj, interpretation, "surface", (-(hx - m), -(hy - m), c, 0, 0, -math.pi), (hx - m, hy - m, c, 0, 0, math.pi), X_WR=X_WR,
                    approach=_approach(spec, 2, 1.0))]


def parking(obj, spec, interpretation, ee):
    """(x, y, heading) boxes: forwards into the spot and reversing in."""
    x, y, _ = obj.pose.xyz
    yaw = obj.pose.rpy[2]
    tol, htol = spec["position_tolerance"], spec["heading_tolerance"] * DEG
    out = []
    for label, heading in (("forwards", yaw), ("reversing", yaw + math.pi)):
        lo_h = math.remainder(heading - htol, 2 * math.pi)
        hi_h = math.remainder(heading + htol, 2 * math.pi)
        out.append(_region(ConfigRegion, obj, interpretation, label, (x - tol, y - tol, lo_h), (x + tol, y + tol, hi_h), wrap=(2,)))
    return out


TEMPLATES = {"top": top, "side_faces": side_faces, "side_around": side_around, "surface": surface, "parking": parking}
