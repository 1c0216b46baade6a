"""C-space goal regions: a box in the planned coordinates (e.g. a car's x, y, heading)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.geometry import Pose
from lazyground.regions.base import GoalRegion, RegionDrawing, register_region

MIN_DRAWN_HEIGHT = 1.0  # m: a flat spot is drawn as a box this tall so it shows from above and aside


@register_region
@dataclass(frozen=True)
class ConfigRegion(GoalRegion):
    """A box of planned-coordinate values, sampled directly (:class:`lazyground.goals.ConfigGoalSource`)."""

    kind = "config"

    def drawing(self, scene) -> RegionDrawing:
        """The object's footprint, one box per object (its regions share the drawing's name)."""
        obj = scene.object(self.object)
        hx, hy, hz = obj.geometry.half_extents()
        size = (2 * hx, 2 * hy, max(2 * hz, MIN_DRAWN_HEIGHT))
        return RegionDrawing(self.object, size, obj.pose.pose().compose(Pose((0.0, 0.0, size[2] / 2))))

    def reached(self, q: np.ndarray, world=None, tol: float = 1e-6) -> bool:
        """Whether ``q`` lies in the box (no world needed)."""
        return self.contains(q, tol)
