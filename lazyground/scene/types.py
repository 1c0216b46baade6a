"""The object types (``types.yaml``): what each type affords (grasps, placements, parking) and holds.

The table belongs with the scene: the grounding reads its goal-region templates
(:mod:`grounding.regions`), the Drake world and the plots what an occupied spot holds.
A scene's ``grasp_types`` overrides entries per type.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from lazyground.scene.schema import Geometry, Scene, SceneObject
from lazyground.typed_yaml import SceneError, load_dataclass, load_yaml

TYPES_FILE = Path(__file__).with_name("types.yaml")


@lru_cache(maxsize=1)
def default_types() -> dict:
    return load_yaml(TYPES_FILE.read_text())


def type_definitions(scene: Scene | None) -> dict:
    """The bundled definitions with the scene's ``grasp_types`` overrides applied per type."""
    types = dict(default_types())
    if scene is not None and scene.grasp_types:
        types.update(scene.grasp_types)
    return types


def occupant_geometry(obj: SceneObject, scene: Scene | None = None) -> Geometry | None:
    """What an occupied ``obj`` holds: its own ``occupant``, else its type's; None if neither says.

    Raises:
        SceneError: the type's ``occupant`` entry is not a geometry.
    """
    if obj.occupant is not None:
        return obj.occupant
    spec = type_definitions(scene).get(obj.type, {}).get("occupant")
    if spec is None:
        return None
    try:
        return load_dataclass(spec, Geometry, f"{obj.type}.occupant")
    except SceneError as exc:
        raise SceneError(f"lazyground/scene/types.yaml: {exc}") from None
