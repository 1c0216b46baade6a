"""Scene files: the schema and the strict loader (no pydrake)."""

from lazyground.scene.loader import load_scene, parse_scene
from lazyground.scene.schema import Expectation, Geometry, Obstacle, PlannerSpec, PoseSpec, RobotSpec, Scene, SceneObject
from lazyground.typed_yaml import SceneError

__all__ = [
    "Expectation", "Geometry", "Obstacle", "PlannerSpec", "PoseSpec", "RobotSpec", "Scene", "SceneError",
    "SceneObject", "load_scene", "parse_scene",
]
