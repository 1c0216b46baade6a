"""Minimal grounding for the core slice: "park" and "pick up a/the <type>".

The full language (synonyms, attributes, locations, place) replaces this module.
"""

from __future__ import annotations

import re

from grounding.model import Grounding, GroundingError, Interpretation
from grounding.regions import regions_for
from lazyground.scene.schema import Scene

PARK = re.compile(r"^\s*(park( the car)?|find a parking spot|park in a free spot)\s*[.!]?\s*$", re.I)
PICK = re.compile(r"^\s*pick up (a|an|the|any) (\w+)\s*[.!]?\s*$", re.I)


def ground(request: str, scene: Scene) -> Grounding:
    if PARK.match(request or ""):
        spots = [o for o in scene.objects if o.type == "parking_spot" and not o.occupied]
        if not spots:
            raise GroundingError("no free parking_spot in this scene")
        return Grounding(request, "park", tuple(
            Interpretation(f"park:{s.id}", "park", (s.id,), None, regions_for(s, "park", f"park:{s.id}", scene)) for s in spots
        ))
    m = PICK.match(request or "")
    if m:
        objs = scene.objects_of_type(m.group(2).lower())
        if not objs:
            raise GroundingError(f"no {m.group(2)!r} in this scene")
        return Grounding(request, "pick", tuple(
            Interpretation(f"pick:{o.id}", "pick", (o.id,), None, regions_for(o, "pick", f"pick:{o.id}", scene)) for o in objs
        ))
    raise GroundingError(f"cannot understand {request!r}; try \"park\" or \"pick up a can\"")
