"""Colours shared by the plots and the Meshcat view (paper Figs. 4 and 6).

The scene bodies' own colours (objects, obstacles, occupants) live with the scene: :mod:`lazyground.scene.colours`.
"""

from __future__ import annotations

import numpy as np

TREE_RGBA = (0.05, 0.15, 0.55, 1.0)  # dark blue: the tree's branches
GOAL_BIASED_RGBA = (0.1, 0.45, 1.0, 1.0)  # blue: nodes added by goal-biased extensions
FAILED_RGBA = (0.9, 0.05, 0.05, 1.0)  # red: origins of failed goal-biased extensions
PATH_RGBA = (0.35, 0.8, 1.0, 1.0)  # light blue: the solution path
REGION_RGBA = (0.1, 0.8, 0.25, 0.25)  # translucent green: goal regions / free spots
OBSTACLE_RGBA = (0.8, 0.15, 0.1, 1.0)  # red: obstacles
CAR_RGBA = (1.0, 1.0, 1.0, 1.0)  # white: the planned car
PATH_DARK_RGBA = (0.0, 0.45, 0.75, 1.0)  # darker blue: direction of travel, forwards
REVERSE_RGBA = (1.0, 0.5, 0.0, 1.0)  # orange: direction of travel, reverse gear
LIMITS_RGBA = (0.25, 0.25, 0.25, 1.0)  # dark grey: the lot's limits (robot.limits), where the car's reference point may go

CAR_FOOTPRINT = (4.5, 1.8)  # m: the planned car's length and width (models/car/car.urdf)

# Goal-sample weights: penalised (0) red, through yellow, to rewarded (1) green.
_WEIGHT_ANCHORS = np.array([[0.85, 0.1, 0.1], [0.95, 0.8, 0.1], [0.1, 0.7, 0.2]])


def weight_rgba(weight: float, alpha: float = 1.0) -> tuple[float, float, float, float]:
    """The colour of a goal sample with reward-penalty weight ``weight`` in [0, 1]."""
    w = float(np.clip(weight, 0.0, 1.0)) * 2.0
    k = min(int(w), 1)
    r, g, b = _WEIGHT_ANCHORS[k] + (w - k) * (_WEIGHT_ANCHORS[k + 1] - _WEIGHT_ANCHORS[k])
    return (float(r), float(g), float(b), alpha)
