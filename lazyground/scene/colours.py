"""The colours of scene bodies in the Drake world's visual geometry (Meshcat): below drake, which registers them."""

from __future__ import annotations

import re

# Scene bodies in the Drake world's visual geometry (Meshcat).
OBSTACLE_SCENE_RGBA = (0.8, 0.25, 0.2, 1.0)  # walls, islands, shelves given as obstacles
OCCUPANT_RGBA = (0.75, 0.2, 0.2, 1.0)  # what occupies an occupied object (a parked car)
DEFAULT_OBJECT_RGBA = (0.3, 0.6, 0.9, 1.0)
COLOR_RGBA = {  # an object's `color:` attribute
    "red": (0.85, 0.1, 0.1, 1.0), "green": (0.1, 0.7, 0.2, 1.0), "blue": (0.15, 0.3, 0.9, 1.0),
    "yellow": (0.95, 0.85, 0.1, 1.0), "white": (0.95, 0.95, 0.95, 1.0), "black": (0.1, 0.1, 0.1, 1.0),
    "orange": (1.0, 0.55, 0.0, 1.0), "brown": (0.55, 0.35, 0.2, 1.0), "grey": (0.6, 0.6, 0.6, 1.0),
    "gray": (0.6, 0.6, 0.6, 1.0), "purple": (0.55, 0.2, 0.75, 1.0),
}
TYPE_RGBA = {"table": (0.6, 0.45, 0.3, 1.0), "shelf": (0.55, 0.55, 0.6, 1.0), "parking_spot": (0.2, 0.8, 0.3, 0.35)}  # objects without a known colour


def object_rgba(obj) -> tuple:
    """The colour of a scene object: its ``color`` if known, else its type's, else a default blue."""
    return color_rgba(obj.color) or TYPE_RGBA.get(obj.type, DEFAULT_OBJECT_RGBA)


def obstacle_rgba(obstacle) -> tuple:
    """The colour of an obstacle: its ``color`` if known (issue 34: a brown table leg rendered red), else red."""
    return color_rgba(obstacle.color) or OBSTACLE_SCENE_RGBA


def color_rgba(color: str | None) -> tuple | None:
    """RGBA of a colour name (``COLOR_RGBA``) or ``#rrggbb``; None for none or one not known."""
    if not color:
        return None
    color = color.strip().lower()
    if re.fullmatch(r"#[0-9a-f]{6}", color):
        return tuple(int(color[k:k + 2], 16) / 255 for k in (1, 3, 5)) + (1.0,)
    return COLOR_RGBA.get(color)
