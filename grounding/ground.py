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
from grounding.model import Group, Grounding, GroundingError, Interpretation
from grounding.parse import parse
from grounding.phrases import Clause, Location, NounPhrase, Quantity, Request
from grounding.regions import check_types, regions_for
from grounding.resolve import Resolver, inventory
from lazyground.robots.end_effector import end_effector_of
from lazyground.scene.schema import Scene, SceneObject

MAX_CHARS = 500
AND_REFUSED = "not supported: {!r} joins two objects or actions; ask for one at a time"


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
    clause = one_clause(parse(lex.tokens(text), lex, inventory(scene)))
    res = Resolver(scene, lex)
    if several(clause):
        return ground_several(request, clause, res, scene)
    action, obj, target = _frame(clause, res)
    ee = end_effector_of(scene.robot) if action != "park" else None
    notes: list[str] = []
    if action == "park":
        spots = res.choice(target, "park")
        notes += _ambiguity(target, spots, "free parking spots")
        # (the robot's end effector read once, not per spot: its files' paths resolved 512 times were most of
        # grounding a 512-spot lot, #33)
        park_ee = end_effector_of(scene.robot) if spots else None
        interps = [_interpretation("park", s, None, scene, clause.manner, ee=park_ee) for s in spots]  # a manner only shapes parking
        if clause.manner:
            notes.append(f"{clause.manner} into the spot only")
    else:
        objs = res.choice(obj, "pick")
        notes += _ambiguity(obj, objs, _what(obj, objs))
        if action == "pick":
            interps = [_interpretation("pick", o, None, scene, ee=ee) for o in objs]
        else:
            targets = res.choice(target, "support")
            notes += _ambiguity(target, targets, "surfaces")
            memo: dict = {}
            interps = [_interpretation("place", o, t, scene, ee=ee, memo=memo) for o in objs for t in targets if o.id != t.id]
            if not interps:
                raise GroundingError(f"nothing to place: {objs[0].id} cannot be put on itself")
        interps, unfit = _graspable(interps, scene, ee)
        notes += unfit
    return Grounding(request, action, tuple(interps), tuple(notes + res.notes))


def one_clause(request: Request) -> Clause:
    """The single action a request asks for: joins "find a spot and park" and "grab X and put it on Y".

    Raises:
        GroundingError: a negated action, or two actions that do not make one.
    """
    clauses = list(request.clauses)
    for c in clauses:
        if c.negated:
            raise GroundingError(f"not supported: a negated action ('{c.verb.text}' after 'not'); say what to do instead")
    while len(clauses) > 1:
        a, b = clauses[0], clauses[1]
        if _refers_back(b) and a.objects and b.verb.value == "place" and a.verb.value == "pick":
            joined = Clause(b.verb, a.objects, a.pps + b.pps, b.manner, to_person=b.to_person, free_target=b.free_target)
        elif _parks(a) and _parks(b) and not (a.objects and b.objects and not _refers_back(b)):
            first, second = (a, b) if a.objects or a.pps else (b, a)
            pps = first.pps + tuple(pp for pp in second.pps if not all(x.head == "pronoun" for x in pp.alternatives))
            verb = a.verb if a.verb.value == "park" else b.verb
            joined = Clause(verb, first.objects, pps, a.manner or b.manner, free_target=a.free_target or b.free_target)
        else:
            raise GroundingError(AND_REFUSED.format(request.conjunction or "and"))
        clauses[:2] = [joined]
    return clauses[0]


def several(c: Clause) -> bool:
    """Whether a clause asks for several objects: "clear", "a cup and a box", "two cans", "all the cups"."""
    phrases = [a for alts in c.objects for a in alts]
    if any(a.head in ("robot", "") for a in phrases):  # "park 2 cars": _frame says why not
        return False
    return c.verb.value == "clear" or len(c.objects) > 1 or any(not a.quantity.single for a in phrases)


def _refers_back(c: Clause) -> bool:
    """A clause whose object is "it"/"them", the car, or missing ("... and put it on the table", "... and park the car")."""
    return not c.objects or all(a.head in ("pronoun", "robot") for alts in c.objects for a in alts)


def _parks(c: Clause) -> bool:
    return c.verb.value == "park" or (c.verb.value == "pick" and any(a.head in ("noun", "idref") and a.value == "parking_spot"
                                                                     for alts in c.objects for a in alts))


def _graspable(interps: list[Interpretation], scene: Scene, ee) -> tuple[list[Interpretation], list[str]]:
    """Drop interpretations whose object no grasp fits (grounding/grasps.py), with a note each.

    Raises:
        GroundingError: no object fits the gripper (the notes, with the numbers).
    """
    keep = [i for i in interps if i.goal_regions]
    dropped = sorted({i.objects[0] for i in interps if not i.goal_regions})
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


def _frame(c: Clause, res: Resolver) -> tuple[str, tuple[NounPhrase, ...], tuple[NounPhrase, ...]]:
    """Decide the action and which phrases are the object and the target (spot or surface)."""
    verb, pps = c.verb, list(c.pps)
    if verb.value == "clear":
        raise GroundingError(f"not supported: {verb.text!r} asks to move every object off a surface; the robot handles one object at a time")
    if len(c.objects) > 1:
        raise GroundingError(AND_REFUSED.format(c.conjunction or "and"))
    obj = c.object
    if not obj and c.free_target and verb.value == "pick":  # "take any of them"
        obj, c = (NounPhrase("", "wildcard", determiner="indefinite", free=True),), replace(c, free_target=False)
    robot_only = bool(obj) and all(a.head == "robot" or (a.head == "pronoun" and verb.value == "park") for a in obj)
    for a in obj:
        if a.head in ("robot", "") and not a.quantity.single:  # "park 2 cars"
            raise GroundingError(f"not supported: {a.quantity.word!r} asks for several objects; the robot handles one at a time")
    leave = robot_only and verb.value == "place" and (not pps or c.free_target or _is_spot(pps[-1].alternatives, res))
    anything = bool(obj) and all(a.free or (a.head in ("wildcard", "") and all(m.kind == "relation" for m in a.modifiers)) for a in obj)
    if verb.value == "park" or _is_spot(obj, res) or leave:
        if obj and not _is_spot(obj, res) and not robot_only and not anything:
            raise GroundingError(f"{verb.text!r} needs a parking spot, not {obj[0].full()!r}; try 'park in a free spot'")
        rows = lambda pp: all(a.head == "row" for a in pp.alternatives)  # noqa: E731  ("in row c" locates, it is no spot)
        if _is_spot(obj, res) or (anything and not robot_only):
            spot = obj
        elif not c.free_target and any(not rows(pp) for pp in pps):
            spot = pps.pop(max(i for i, pp in enumerate(pps) if not rows(pp))).alternatives
        else:
            spot = (NounPhrase("", determiner="indefinite"),)
        if robot_only and obj[0].modifiers:  # "park the car next to spot 3": the relation places the spot
            spot = tuple(replace(a, modifiers=a.modifiers + obj[0].modifiers) for a in spot)
        return "park", (), _located(spot, pps)
    action = "place" if verb.value == "place" or (pps and pps[-1].prep.value == "target") or c.free_target else "pick"
    if c.to_person and not (pps and pps[-1].prep.value == "target"):
        action = "pick"  # "bring the can to me": the robot carries it
    if not obj:
        raise GroundingError(f"{verb.text!r} needs an object, e.g. '{verb.text} a can'")
    for a in obj:
        if not a.quantity.single:
            word = a.word if a.plural else plural(a.word or "object")
            raise GroundingError(f"not supported: {a.full()!r} asks for several objects; the robot handles one at a time (try 'one of the {word}')")
        if a.head == "pronoun":
            raise GroundingError(f"not supported: {a.word!r} (nothing to refer back to); name the object, e.g. 'pick up the can'")
    if action == "pick":
        return "pick", _located(obj, pps), ()
    if c.free_target:
        return "place", _located(obj, pps), (NounPhrase("", determiner="indefinite", free=True),)
    if not pps:
        rel = next((m for a in obj for m in a.modifiers if m.kind == "relation"), None)
        if rel is not None:  # "put the box under the table": a place beside an object is no goal region
            raise GroundingError(f"not supported: placing {rel.word} {rel.landmark.full()}; say a surface to put it on, e.g. 'on the table'")
        raise GroundingError(f"{verb.text!r} needs a place, e.g. '{verb.text} the can on the table'")
    target = pps.pop().alternatives
    return "place", _located(obj, pps), target


def _is_spot(alts: tuple[NounPhrase, ...], res: Resolver) -> bool:
    def spot(a: NounPhrase) -> bool:
        type_name = a.value if a.head in ("noun", "idref") and a.value else res.scene.object(a.value).type if a.head == "id" else None
        if a.head == "idref" and not a.value:
            return any(res.has_role(o.type, "park") for o in res.scene.objects)
        return type_name is not None and res.has_role(type_name, "park") and not res.has_role(type_name, "pick")
    return bool(alts) and all(spot(a) for a in alts)


def _located(alts: tuple[NounPhrase, ...], pps: list) -> tuple[NounPhrase, ...]:
    """Attach location phrases ("on the table") to every alternative."""
    locs = tuple(Location(pp.prep.text, pp.alternatives) for pp in pps)
    return tuple(replace(a, locations=a.locations + locs) for a in alts)


def _interpretation(action: str, obj: SceneObject, target: SceneObject | None, scene: Scene, manner: str = "",
                    ee=None, memo: dict | None = None) -> Interpretation:
    iid = f"{action}:{obj.id}" + (f":{target.id}" if target is not None else "")
    if action == "park":
        regions = regions_for(obj, "park", iid, scene, ee)
        if manner:  # "reverse into spot 4": only the goal regions with that heading
            regions = tuple(r for r in regions if r.label == manner) or regions
        return Interpretation(iid, action, (obj.id,), None, regions)
    place = _regions(target, "support", iid, scene, ee, memo) if target is not None else ()
    return Interpretation(iid, action, (obj.id,), target.id if target else None, _regions(obj, "pick", iid, scene, ee, memo), place)


def _regions(obj: SceneObject, role: str, iid: str, scene: Scene, ee, memo: dict | None) -> tuple:
    """``regions_for``, built once per (object, role) in a request and relabelled per interpretation
    ("put a box on a shelf": 5 boxes x 9 boards share 5 + 9 region sets)."""
    if memo is None:
        return regions_for(obj, role, iid, scene, ee)
    key = (obj.id, role)
    if key not in memo:
        memo[key] = regions_for(obj, role, iid, scene, ee)
    return tuple(r if r.interpretation == iid else replace(r, interpretation=iid) for r in memo[key])


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


# --- several objects (issue #30) ------------------------------------------------------------
# Requests for several objects (issue #30): "put two cans on the table", "put all the cups on the
# shelf", "put a cup and a box on the shelf", "clear the table (onto the counter)".
#
# The grounding stays lazy: each "and"-part becomes a :class:`~grounding.model.Group` of candidate
# objects and how many of them to move; every candidate keeps its place interpretations (one per
# target surface), and the task (``lazyground/tasks/several.py``) picks, step by step, whichever
# candidate and placement the planner reaches. Candidates already resting on a target are named in
# ``Group.already`` (reported, not moved).

SOME = 2  # "some cans", "a few boxes": how many are moved


def ground_several(request: str, c: Clause, res: Resolver, scene: Scene) -> Grounding:
    """The grounding of a several-object request: groups in order, every candidate's place interpretations.

    "pick up two cans" (action ``pick``): the robot holds one object at a time, so every object but the
    last is put down on a stow surface (:func:`stow_surfaces`); each candidate has a pick interpretation
    (the last step) and place interpretations to its stow surfaces.

    Raises:
        GroundingError: a count above what the scene holds, nothing to clear, nowhere to stow, or what
            :func:`grounding.ground._frame` refuses.
    """
    ee = end_effector_of(scene.robot)
    notes: list[str] = []
    if c.verb.value == "clear":
        parts, targets = _clearing(c, res, scene, notes)
    else:
        parts, targets = _parts(c, res, notes)
    picking = targets is None
    memo: dict = {}
    interps, groups = [], []
    for phrase, objs, count in parts:
        if picking:
            mine = [i for o in objs for i in [_interpretation("pick", o, None, scene, ee=ee)]
                    + [_interpretation("place", o, t, scene, ee=ee, memo=memo) for t in stow_surfaces(o, res, scene)]]
        else:
            mine = [_interpretation("place", o, t, scene, ee=ee, memo=memo) for o in objs for t in targets if o.id != t.id]
        mine, unfit = _graspable(mine, scene, ee) if mine else ([], [])
        notes += unfit
        ids = tuple(dict.fromkeys(i.objects[0] for i in mine))
        if count is not None and count > len(ids):
            raise GroundingError(f"{phrase!r} asks for {count}; the scene has {len(ids)} that fit "
                                 f"({', '.join(ids) or 'none'})")
        target_ids = set() if picking else {t.id for t in targets}
        already = tuple(o for o in ids if res.support(scene.object(o)) in target_ids)
        interps += [i for i in mine if i.id not in {j.id for j in interps}]
        groups.append(Group(phrase, ids, count, already))
    if not interps:
        raise GroundingError(f"nothing to move for {request!r}")
    if picking:
        _check_stow(groups, interps, scene, notes)
    return Grounding(request, "pick" if picking else "place", tuple(interps), tuple(notes + res.notes), tuple(groups))


def stow_surfaces(obj: SceneObject, res: Resolver, scene: Scene) -> list[SceneObject]:
    """Where ``obj`` may be put down to free the gripper: the scene's ``stow:`` surfaces, else every
    support surface but the one it rests on (putting it back where it was would undo the pick).

    Raises:
        GroundingError: a ``stow:`` entry that is no support surface.
    """
    if scene.stow:
        out = [scene.object(s) for s in scene.stow]
        bad = [o.id for o in out if not res.has_role(o.type, "support")]
        if bad:
            raise GroundingError(f"stow: {bad[0]!r} is a {scene.object(bad[0]).type}, not a surface to put things on")
        return [o for o in out if o.id != obj.id]
    return [o for o in scene.objects if res.has_role(o.type, "support") and o.id not in (obj.id, res.support(obj))]


def _check_stow(groups, interps, scene: Scene, notes: list[str]) -> None:
    """Say where objects are put down; refuse when more than one is asked for and none can be put down anywhere."""
    steps = sum(len(g.objects) if g.count is None else g.count for g in groups)
    if steps < 2:
        return
    places = sorted({i.target for i in interps if i.action == "place"})
    if not places:
        raise GroundingError("the robot holds one object at a time and the scene has no surface to put the others "
                             "down on; declare one with 'stow: [<surface id>]'")
    where = "the scene's stow: " if scene.stow else "no stow: in the scene, so any surface other than its own: "
    notes.append(f"one gripper: every object but the last is put down first ({where}{', '.join(places)}); the last is held")


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
    """Per "and"-part: (phrase, candidate objects, count); and the target surfaces (the same for every part;
    None when the parts are picked up, not put somewhere)."""
    parts, targets = [], None
    for alts in c.objects:
        single = tuple(replace(a, quantity=Quantity()) for a in alts)
        action, obj, target = _frame(replace(c, objects=(single,)), res)
        if action == "park":
            _frame(replace(c, objects=(alts,)), res)  # says why for the phrase as typed
            raise GroundingError(AND_REFUSED.format(c.conjunction or "and"))
        if parts and (targets is None) != (action == "pick"):
            raise GroundingError(AND_REFUSED.format(c.conjunction or "and"))
        objs = res.choice(obj, "pick")
        if action == "place" and targets is None:
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

