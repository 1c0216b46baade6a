"""Requests for several objects (issue #30): "put two cans on the table", "put all the cups on the
shelf", "put a cup and a box on the shelf", "clear the table (onto the counter)".

The grounding stays lazy: each "and"-part becomes a :class:`~grounding.model.Group` of candidate
objects and how many of them to move; every candidate keeps its place interpretations (one per
target surface), and the task (``lazyground/tasks/several.py``) picks, step by step, whichever
candidate and placement the planner reaches. Candidates already resting on a target are named in
``Group.already`` (reported, not moved).
"""

from __future__ import annotations

from dataclasses import replace

from grounding.ground import AND_REFUSED, _ambiguity, _frame, _graspable, _interpretation, _what
from grounding.model import Group, Grounding, GroundingError
from grounding.phrases import Clause, NounPhrase, Quantity
from grounding.resolve import Resolver
from lazyground.robots.end_effector import end_effector_of
from lazyground.scene.schema import Scene

SOME = 2  # "some cans", "a few boxes": how many are moved


def ground_several(request: str, c: Clause, res: Resolver, scene: Scene) -> Grounding:
    """The grounding of a several-object request: groups in order, every candidate's place interpretations.

    Raises:
        GroundingError: picking several objects without a place, a count above what the scene holds,
            nothing to clear, or what :func:`grounding.ground._frame` refuses.
    """
    ee = end_effector_of(scene.robot)
    notes: list[str] = []
    if c.verb.value == "clear":
        parts, targets = _clearing(c, res, scene, notes)
    else:
        parts, targets = _parts(c, res, notes)
    memo: dict = {}
    interps, groups = [], []
    for phrase, objs, count in parts:
        mine = [_interpretation("place", o, t, scene, ee=ee, memo=memo) for o in objs for t in targets if o.id != t.id]
        mine, unfit = _graspable(mine, scene, ee) if mine else ([], [])
        notes += unfit
        ids = tuple(dict.fromkeys(i.objects[0] for i in mine))
        if count is not None and count > len(ids):
            raise GroundingError(f"{phrase!r} asks for {count}; the scene has {len(ids)} that fit "
                                 f"({', '.join(ids) or 'none'})")
        target_ids = {t.id for t in targets}
        already = tuple(o for o in ids if res.support(scene.object(o)) in target_ids)
        interps += [i for i in mine if i.id not in {j.id for j in interps}]
        groups.append(Group(phrase, ids, count, already))
    if not interps:
        raise GroundingError(f"nothing to move for {request!r}")
    return Grounding(request, "place", tuple(interps), tuple(notes + res.notes), tuple(groups))


def _count(q: Quantity) -> int | None:
    """How many objects a quantity asks for; None: all."""
    if q.kind == "n":
        return q.count
    if q.kind == "some":
        return q.count or SOME
    if q.kind == "one":
        return 1
    return None if q.kind in ("all", "each") and q.count is None else q.count


def _parts(c: Clause, res: Resolver, notes: list[str]):
    """Per "and"-part: (phrase, candidate objects, count); and the target surfaces (the same for every part)."""
    parts, targets = [], None
    for alts in c.objects:
        single = tuple(replace(a, quantity=Quantity()) for a in alts)
        action, obj, target = _frame(replace(c, objects=(single,)), res)
        if action != "place":  # the robot holds one object at a time: _frame says so for the phrase as typed
            _frame(replace(c, objects=(alts,)), res)
            raise GroundingError(AND_REFUSED.format(c.conjunction or "and"))
        objs = res.choice(obj, "pick")
        if targets is None:
            targets = res.choice(target, "support")
            notes += _ambiguity(target, targets, "surfaces")
        q = alts[0].quantity
        count = _count(q)
        if count == 1:
            notes += _ambiguity(obj, objs, _what(obj, objs))
        parts.append((alts[0].full(), objs, count))
    return parts, targets


def _clearing(c: Clause, res: Resolver, scene: Scene, notes: list[str]):
    """"clear the table (onto the counter)": every movable object on the surface, to the stated or any other surface."""
    surfaces = res.choice(c.object or (NounPhrase("", determiner="indefinite"),), "support")
    cleared = {s.id for s in surfaces}
    objs = [o for o in scene.objects if res.has_role(o.type, "pick") and res.support(o) in cleared]
    if not objs:
        raise GroundingError(f"nothing to clear: no movable object rests on {', '.join(sorted(cleared))}")
    stated = [pp for pp in c.pps if pp.prep.value == "target"]
    if stated:
        targets = [t for t in res.choice(stated[-1].alternatives, "support") if t.id not in cleared]
    else:
        targets = [o for o in scene.objects if res.has_role(o.type, "support") and o.id not in cleared]
        notes.append(f"clearing {', '.join(sorted(cleared))}: no place said, so any other surface "
                     f"({', '.join(t.id for t in targets)})")
    if not targets:
        raise GroundingError(f"nowhere to put what is on {', '.join(sorted(cleared))}: name another surface")
    return [(f"everything on {', '.join(sorted(cleared))}", objs, None)], targets

