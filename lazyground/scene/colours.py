"""The colours of scene bodies in the Drake world's visual geometry (Meshcat): below drake, which registers them."""

from __future__ import annotations

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
    if obj.color and obj.color.lower() in COLOR_RGBA:
        return COLOR_RGBA[obj.color.lower()]
    return TYPE_RGBA.get(obj.type, DEFAULT_OBJECT_RGBA)
