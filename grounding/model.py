"""What grounding produces: interpretations of a request and their goal regions."""

from __future__ import annotations

from dataclasses import dataclass

from lazyground.regions import GoalRegion

ACTIONS = ("pick", "place", "park")


class GroundingError(ValueError):
    """A request that cannot be grounded in a scene; the message is one line for the user."""


@dataclass(frozen=True)
class Interpretation:
    """One valid reading I_i of a request: an action on an object (and a target).

    For ``place`` the interpretation names the object to carry in ``objects``
    and the surface in ``target``; ``goal_regions`` are the grasp regions of the
    object and ``place_regions`` the placement regions on the target.
    """

    id: str
    action: str
    objects: tuple[str, ...]
    target: str | None
    goal_regions: tuple[GoalRegion, ...]
    place_regions: tuple[GoalRegion, ...] = ()

    def to_json(self) -> dict:
        out = {
            "id": self.id,
            "action": self.action,
            "objects": list(self.objects),
            "target": self.target,
            "goal_regions": [r.to_json() for r in self.goal_regions],
        }
        if self.place_regions:
            out["place_regions"] = [r.to_json() for r in self.place_regions]
        return out


@dataclass(frozen=True)
class Grounding:
    """Every interpretation of ``request`` that fits the scene; choosing is the planner's job."""

    request: str
    action: str
    interpretations: tuple[Interpretation, ...]
    notes: tuple[str, ...] = ()  # e.g. "'the can' matches 3 cans: all kept"

    @property
    def ambiguous(self) -> bool:
        return len(self.interpretations) > 1

    @property
    def goal_regions(self) -> tuple[GoalRegion, ...]:
        return tuple(r for i in self.interpretations for r in i.goal_regions)

    def to_json(self) -> dict:
        return {
            "request": self.request,
            "action": self.action,
            "ambiguous": self.ambiguous,
            "notes": list(self.notes),
            "interpretations": [i.to_json() for i in self.interpretations],
        }
