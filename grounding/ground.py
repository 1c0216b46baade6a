"""``ground(request, scene)``: a text request -> every interpretation that fits -> goal regions.

Three actions (see docs/requests.md for the language):

* ``pick``  — "pick up a can": one interpretation ``pick:<obj>`` per matching
  object; goal regions are the object's grasp regions.
* ``place`` — "put a cup on the table": one ``place:<obj>:<target>`` per
  (object, surface) pair; goal regions are the object's grasps and
  ``place_regions`` the surface's placement regions.
* ``park``  — "park", "find a parking spot": one ``park:<spot>`` per free spot.

Ambiguity is kept, not resolved: choosing is the planner's job.
"""

from __future__ import annotations

from dataclasses import replace

from grounding.grasps import fit_note
from grounding.lexicon import Lexicon, load_lexicon, plural
from grounding.model import Grounding, GroundingError, Interpretation
from grounding.parse import NounPhrase, Phrase, parse
from grounding.regions import check_types, regions_for
from grounding.resolve import Resolver, inventory
from lazyground.robots.end_effector import end_effector_of
from lazyground.scene.schema import Scene, SceneObject

MAX_CHARS = 500


def ground(request: str, scene: Scene, lexicon: Lexicon | None = None) -> Grounding:
    """Every interpretation of ``request`` in ``scene``, with goal regions.

    Args:
        request: the user's text, e.g. "could you grab the red can on the left shelf?".
        scene: the loaded scene.
        lexicon: the word table (default: ``grounding/lexicon.yaml`` + $LAZYGROUND_LEXICON).

    Raises:
        GroundingError: one line saying which word found nothing, what is not
            supported, or what the scene holds instead; or an object type that
            neither ``types.yaml`` nor the scene's ``grasp_types`` defines.
    """
    text = _check_text(request)
    check_types(scene)
    lex = (lexicon or load_lexicon()).for_scene(scene)
    phrase = parse(lex.tokens(text), lex, inventory(scene))
    res = Resolver(scene, lex)
    action, obj, target = _frame(phrase, res)
    notes: list[str] = []
    if action == "park":
        spots = res.choice(target, "park")
        notes += _ambiguity(target, spots, "free parking spots")
        interps = [_interpretation("park", s, None, scene) for s in spots]
    else:
        objs = res.choice(obj, "pick")
        notes += _ambiguity(obj, objs, _what(obj, objs))
        if action == "pick":
            interps = [_interpretation("pick", o, None, scene) for o in objs]
        else:
            targets = res.choice(target, "support")
            notes += _ambiguity(target, targets, "surfaces")
            interps = [_interpretation("place", o, t, scene) for o in objs for t in targets if o.id != t.id]
            if not interps:
                raise GroundingError(f"nothing to place: {objs[0].id} cannot be put on itself")
        interps, unfit = _graspable(interps, scene)
        notes += unfit
    return Grounding(request, action, tuple(interps), tuple(notes + res.notes))


def _graspable(interps: list[Interpretation], scene: Scene) -> tuple[list[Interpretation], list[str]]:
    """Drop interpretations whose object no grasp fits (grounding/grasps.py), with a note each.

    Raises:
        GroundingError: no object fits the gripper (the notes, with the numbers).
    """
    keep = [i for i in interps if i.goal_regions]
    dropped = sorted({i.objects[0] for i in interps if not i.goal_regions})
    ee = end_effector_of(scene.robot)
    unfit = [fit_note(scene.object(o), ee) for o in dropped]
    if not keep:
        raise GroundingError("; ".join(unfit))
    return keep, unfit


def _check_text(request) -> str:
    if not isinstance(request, str):
        raise GroundingError(f"a request is text, got {type(request).__name__}")
    if len(request) > MAX_CHARS:
        raise GroundingError(f"request too long: {len(request)} characters (limit {MAX_CHARS})")
    bad = next((c for c in request if not c.isascii()), None)
    if bad is not None:
        raise GroundingError(f"only plain ASCII requests are understood; found {bad!r} at position {request.index(bad)}")
    return request


def _frame(p: Phrase, res: Resolver) -> tuple[str, tuple[NounPhrase, ...], tuple[NounPhrase, ...]]:
    """Decide the action and which phrases are the object and the target (spot or surface)."""
    verb, obj, pps = p.verb, p.object, list(p.pps)
    if verb.value == "park" or _is_spot(obj, res):
        if obj and not _is_spot(obj, res) and not all(a.head in ("robot", "pronoun") for a in obj):
            raise GroundingError(f"{verb.text!r} needs a parking spot, not {obj[0].full()!r}; try 'park in a free spot'")
        if _is_spot(obj, res):
            spot = obj
        elif pps:
            spot = pps.pop()[1]
        else:
            spot = (NounPhrase("", determiner="indefinite"),)
        return "park", (), _located(spot, pps)
    action = "place" if verb.value == "place" or (pps and pps[-1][0].value == "target") else "pick"
    if not obj:
        raise GroundingError(f"{verb.text!r} needs an object, e.g. '{verb.text} a can'")
    for a in obj:
        if a.plural and a.determiner != "indefinite":
            raise GroundingError(f"not supported: {a.full()!r} asks for several objects; the robot handles one at a time (try 'one of the {a.word}')")
    if action == "pick":
        return "pick", _located(obj, pps), ()
    if not pps:
        raise GroundingError(f"{verb.text!r} needs a place, e.g. '{verb.text} the can on the table'")
    target = pps.pop()[1]
    return "place", _located(obj, pps), target


def _is_spot(alts: tuple[NounPhrase, ...], res: Resolver) -> bool:
    def spot(a: NounPhrase) -> bool:
        type_name = a.value if a.head == "noun" else res.scene.object(a.value).type if a.head == "id" else None
        return type_name is not None and res.has_role(type_name, "park") and not res.has_role(type_name, "pick")
    return bool(alts) and all(spot(a) for a in alts)


def _located(alts: tuple[NounPhrase, ...], pps: list) -> tuple[NounPhrase, ...]:
    """Attach location phrases ("on the table") to every alternative."""
    locs = tuple((prep.text, choice) for prep, choice in pps)
    return tuple(replace(a, locations=a.locations + locs) for a in alts)


def _interpretation(action: str, obj: SceneObject, target: SceneObject | None, scene: Scene) -> Interpretation:
    iid = f"{action}:{obj.id}" + (f":{target.id}" if target is not None else "")
    if action == "park":
        return Interpretation(iid, action, (obj.id,), None, regions_for(obj, "park", iid, scene))
    place = regions_for(target, "support", iid, scene) if target is not None else ()
    return Interpretation(iid, action, (obj.id,), target.id if target else None, regions_for(obj, "pick", iid, scene), place)


def _what(alts: tuple[NounPhrase, ...], objs: list[SceneObject]) -> str:
    types = {o.type for o in objs}
    if len(types) == 1 and alts[0].head == "noun":
        return alts[0].word if alts[0].plural else plural(types.pop().replace("_", " "))
    return "objects"


def _ambiguity(alts: tuple[NounPhrase, ...], objs: list[SceneObject], what: str) -> list[str]:
    """A note when a phrase matches several objects: all are kept for the planner."""
    if len(objs) < 2:
        return []
    text = " or ".join(a.full() for a in alts if a.full()) or "park"
    ids = ", ".join(o.id for o in objs[:6]) + (", ..." if len(objs) > 6 else "")
    definite = any(a.determiner == "definite" for a in alts)
    how = "ambiguous, all kept" if definite else "any will do"
    return [f"'{text}' matches {len(objs)} {what} ({ids}): {how}; the planner goes for whichever is reachable"]
