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
class Group:
    """One "and"-part of a request for several objects (issue #30): which objects may serve, how many.

    ``count`` None means all of them ("all the cups", "the cups", "clear the table"); ``already``
    names the candidates that already rest where the request asks (reported, not moved).
    """

    phrase: str  # as typed: "two cans", "all the cups", "a cup"
    objects: tuple[str, ...]  # candidates (each has place interpretations in the grounding)
    count: int | None
    already: tuple[str, ...] = ()

    def to_json(self) -> dict:
        return {"phrase": self.phrase, "objects": list(self.objects), "count": self.count, "already": list(self.already)}


@dataclass(frozen=True)
class Grounding:
    """Every interpretation of ``request`` that fits the scene; choosing is the planner's job."""

    request: str
    action: str
    interpretations: tuple[Interpretation, ...]
    notes: tuple[str, ...] = ()  # e.g. "'the can' matches 3 cans: all kept"
    groups: tuple[Group, ...] = ()  # several objects (#30): one step per object, groups in order; () = one object

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
            "groups": [g.to_json() for g in self.groups],
        }
