"""Noun phrases -> the scene objects they can mean, with errors that say which word found nothing.

Filters apply in a fixed order — location, relation, colour, attribute, size, position,
superlative, ordinal, then exclusions ("except the red one") — each to what the previous ones
kept, so a message can say "no red can on the table; cans on the table are: blue x2". A negated
filter ("not red", "not on the table") keeps what the filter would drop. Parking spots: occupied
ones are dropped first, except under an ordinal, which counts the whole layout ("the second
spot") and says so when the spot it lands on is occupied. Sizes compare an object with
all objects of its type (a small box stays small wherever it is); positions of
furniture compare whole units; other positions compare the objects still in
play ("the left can on the table" is the left one of the cans on the table).
Explicit scene data wins over geometry: ``size``, ``attributes.level``
(top/middle/bottom) and ``attributes.side`` (left/middle/right).
"""

from __future__ import annotations

import math
import re
from collections import Counter
from dataclasses import replace

from grounding import relations, spatial
from grounding.lexicon import Lexicon, plural
from grounding.model import GroundingError
from grounding.parse import verb_list
from grounding.phrases import Location, Modifier, NounPhrase
from grounding.regions import type_definitions
from lazyground.scene.schema import Scene, SceneObject

ROLE_VERB = {"pick": "pick up", "support": "put things on", "park": "park in", None: "find"}
ORDER = {"state": 0, "relation": 1, "colour": 2, "attribute": 3, "size": 4, "position": 5, "superlative": 6, "ordinal": 7}
VERTICAL = {"top", "bottom"}
HORIZONTAL = {"left", "right"}
DIMENSION = {"left": HORIZONTAL, "right": HORIZONTAL, "top": VERTICAL | {"middle"}, "bottom": VERTICAL | {"middle"},
             "middle": VERTICAL | HORIZONTAL | {"middle"}}
THIRDS = {"high": ("top", "left", "large"), "low": ("bottom", "right", "small"), "mid": ("middle", "middle", "medium")}


def inventory(scene: Scene) -> str:
    """What the scene holds, e.g. "can x3, box x2, table x1"."""
    counts = Counter(o.type for o in scene.objects)
    return ", ".join(f"{t} x{n}" for t, n in counts.items()) or "no objects"


class Resolver:
    """Resolves noun phrases in one scene; collects notes on words that did not narrow anything."""

    def __init__(self, scene: Scene, lexicon: Lexicon):
        self.scene, self.lexicon = scene, lexicon
        self.types = type_definitions(scene)
        self.notes: list[str] = []
        self._support: dict[str, str | None] = {}

    def has_role(self, type_name: str, role: str | None) -> bool:
        return role is None or bool((self.types.get(type_name) or {}).get(role))

    def choice(self, alts: tuple[NounPhrase, ...], role: str | None) -> list[SceneObject]:
        """Union over "X or Y"; an alternative that matches nothing is dropped with a note."""
        found: dict[str, SceneObject] = {}
        errors: list[GroundingError] = []
        for np in alts:
            try:
                found.update((o.id, o) for o in self.np(np, role))
            except GroundingError as exc:
                errors.append(exc)
        if not found:
            raise errors[0]
        self.notes += [f"dropped an alternative: {e}" for e in errors]
        return list(found.values())

    def np(self, np: NounPhrase, role: str | None) -> list[SceneObject]:
        """Every object ``np`` can mean in ``role`` ("pick", "support", "park" or None = landmark)."""
        free_said = any(m.kind == "state" and m.value == "free" for m in np.modifiers)  # "the first free spot" counts free ones
        layout = role == "park" and any(m.kind == "ordinal" for m in np.modifiers) and not free_said
        objs = self._base(np, role, defer_free=role == "park")
        applied: list[tuple[str, str]] = []
        mods = sorted(np.modifiers, key=lambda m: ORDER[m.kind])
        steps = ([("location", loc) for loc in np.locations] + [("relation", m) for m in mods if m.kind == "relation"]
                 + [("free", None)] + [(m.kind, m) for m in mods if m.kind != "relation"])
        for kind, arg in steps:
            if kind == "free":  # spots: occupied ones go after where-words, before which-one words ("the closest spot")
                if role == "park" and not layout:
                    objs = self._free(objs, np)
                continue
            if kind == "state":
                continue
            kept, labels = getattr(self, f"_{kind}")(objs, arg, np)
            if kept is None:
                continue
            if arg.negated:
                kept = [o for o in objs if o not in kept]
            if not kept:
                raise GroundingError(self._nothing(np, applied, objs, labels, arg))
            objs = kept
            applied.append((kind, _said(kind, arg)))
        if np.excluded:
            objs = self._exclude(objs, np)
        if np.different:
            self.notes.append(f"{np.determiner_word!r}: nothing was named before to differ from; any of them will do")
        return self._free(objs, np, ordinal=True) if layout else objs

    def _exclude(self, objs: list[SceneObject], np: NounPhrase) -> list[SceneObject]:
        """Drop what "except ..." / "but ..." / "not ..." names ("any cup except the red one")."""
        gone: set[str] = set()
        for alt in np.excluded:
            try:
                gone |= {o.id for o in self.np(replace(alt, value=alt.value or ""), None)}
            except GroundingError:
                self.notes.append(f"'{alt.full()}' names nothing here, so it excludes nothing")
        kept = [o for o in objs if o.id not in gone]
        if not kept:
            said = " or ".join(a.full() for a in np.excluded)
            raise GroundingError(f"no {np.describe() or 'object'} other than {said}: every match is excluded ({', '.join(sorted(gone & {o.id for o in objs}))})")
        return kept

    # -- the objects a head can name -------------------------------------------------------

    def _base(self, np: NounPhrase, role: str | None, defer_free: bool = False) -> list[SceneObject]:
        verb = ROLE_VERB[role]
        if np.head in ("robot", "pronoun", "person"):
            raise GroundingError(f"cannot {verb} {np.word!r}: that is {'the robot' if np.head != 'person' else 'you'}")
        if np.head == "floor":
            raise GroundingError(f"cannot {verb} the {np.word}")
        if np.head == "id":
            objs = [self.scene.object(np.value)]
        elif np.head == "idref":
            objs = self._idref(np, role)
        elif np.head == "row" and role == "park":  # "park in spot b1 or row t": that row's spots
            objs = [o for row in self._rows(np) for o in row]
        elif np.head == "noun":
            objs = self.scene.objects_of_type(np.value)
            if not objs:
                raise GroundingError(f"no {np.word!r} in this scene; it has: {inventory(self.scene)}")
        else:
            objs = [o for o in self.scene.objects if role is None or (self.has_role(o.type, role) and (role == "park") == self.has_role(o.type, "park"))]
            if not objs and role == "park":
                raise GroundingError(f"no parking spot in this scene; it has: {inventory(self.scene)}")
            if not objs:
                raise GroundingError(f"nothing to {verb} in this scene; it has: {inventory(self.scene)}")
        bad = sorted({o.type for o in objs if not self.has_role(o.type, role)})
        if bad:
            word = np.word or bad[0]
            raise GroundingError(f"cannot {verb} {'an' if word[:1] in 'aeiou' else 'a'} {word}: type {bad[0]!r} has no {role!r} definition in lazyground/scene/types.yaml")
        if role != "park":
            return self._ignore_states(objs, np)
        return objs if defer_free else self._free(objs, np)

    def _idref(self, np: NounPhrase, role: str | None) -> list[SceneObject]:
        """Objects an id said loosely names: "spot 4", "bay b1", "can #3", "spots 3 to 6", "at b1"."""
        pool = self.scene.objects_of_type(np.value) if np.value else [o for o in self.scene.objects if self.has_role(o.type, role)]
        if np.id_range is not None:
            lo, hi = sorted(np.id_range)
            objs = [o for o in pool if (n := _id_number(o.id)) is not None and lo <= n <= hi]
        else:
            objs = [o for o in pool if any(_id_ends_with(o.id, t) for t in np.tails)]
        if not objs:
            said = f"{np.word} {' or '.join(np.tails)}".strip() if not np.id_range else f"{np.word} {np.id_range[0]} to {np.id_range[1]}"
            if not np.value:  # "pick up box9": a word that only looks like an id
                raise GroundingError(f"unknown word {np.word!r}{self.lexicon.ids_with(np.word) or f'; ids here: {_ids(pool)}'}")
            raise GroundingError(f"no {said!r} in this scene{self.lexicon.ids_with(np.word) or f'; ids here: {_ids(pool)}'}")
        return objs

    def _free(self, objs: list[SceneObject], np: NounPhrase, ordinal: bool = False) -> list[SceneObject]:
        state = next((m for m in np.modifiers if m.kind == "state" and m.value != "free"), None)
        if state is not None:
            raise GroundingError(f"not supported: parking in a spot that is {state.word!r}; occupied spots are never goals")
        free = [o for o in objs if not o.occupied]
        if free and ordinal and len(free) < len(objs):
            m = next(m for m in np.modifiers if m.kind == "ordinal")
            taken = ", ".join(o.id for o in objs if o.occupied)
            self.notes.append(f"the {m.word} {np.word or 'spot'} of another row, {taken}, is occupied: kept {', '.join(o.id for o in free)}")
        if free:
            return free
        others = [o for o in self.scene.objects_of_type(objs[0].type) if not o.occupied]
        nearest = sorted(others, key=lambda o: min(relations.gap(o, x) for x in objs))[:3]
        if ordinal:
            m = next(m for m in np.modifiers if m.kind == "ordinal")
            return self._occupied(f"{m.word} {np.word or 'spot'}{' from the ' + m.order if m.order else ''}", objs, nearest)
        if np.head in ("id", "idref") and len(objs) == 1:
            raise GroundingError(f"{objs[0].id} is occupied; free ones: {', '.join(o.id for o in others) or 'none'}")
        if np.modifiers or np.locations or np.head == "idref":
            rel = " ".join(f"{m.word} {' and '.join(lm.full() for lm in m.landmarks)}" for m in np.modifiers if m.kind == "relation")
            return self._occupied(f"{np.describe() or 'spot'} {rel}".strip(), objs, nearest)
        raise GroundingError(f"no free {np.word or 'parking spot'} here: all {len(objs)} are occupied")

    def _occupied(self, said: str, objs: list[SceneObject], nearest: list[SceneObject]) -> list[SceneObject]:
        which = _ids(objs)
        free = ", ".join(o.id for o in nearest) or "none"
        raise GroundingError(f"the {said} is {which}, which {'is' if len(objs) == 1 else 'are'} occupied; the nearest free ones: {free}")

    def _ignore_states(self, objs: list[SceneObject], np: NounPhrase) -> list[SceneObject]:
        for m in np.modifiers:
            if m.kind == "state":
                self.notes.append(f"{m.word!r} ignored: it only describes parking spots")
        return objs

    # -- filters: each returns (kept or None = does not narrow, {id: label} for messages) --

    def _location(self, objs, loc: Location, np):
        if any(a.head == "row" for a in loc.alternatives):  # "on the bottom row": the spots of that row
            ids = {o.id for a in loc.alternatives for row in self._rows(a) for o in row}
            return [o for o in objs if o.id in ids], {o.id: "not in that row" for o in objs}
        landmarks = set()
        for alt in loc.alternatives:
            landmarks |= {spatial.FLOOR} if alt.head == "floor" else {o.id for o in self.choice((alt,), None)}
        labels = {o.id: self.support(o) for o in objs}
        kept = [o for o in objs if labels[o.id] in landmarks]
        return kept, {k: f"on {self.name(v)}" if v else "not on a surface" for k, v in labels.items()}

    def _rows(self, np: NounPhrase) -> list[list[SceneObject]]:
        """The rows of parking spots a "row" phrase names: by name ("row c": ids with that letter), by side
        (left/right as the robot looks; top/bottom as the map is drawn, +y up), nearest/farthest, or n-th from the robot."""
        spots = [o for o in self.scene.objects if self.has_role(o.type, "park")]
        rows = spatial.rows(spots) if spots else []
        if np.value:
            rows = [r for r in rows if all(np.value.lower() in _id_pieces(o.id) for o in r)]
        near = lambda r: min(self.distances(r, None).values())  # noqa: E731
        side = {"left": lambda r: sum(spatial.lateral(o, self.scene) for o in r) / len(r),
                "top": lambda r: sum(o.pose.xyz[1] for o in r) / len(r), "near": lambda r: -near(r)}
        for m in np.modifiers:
            if rows and m.kind in ("position", "superlative") and m.value in {"left", "right", "top", "bottom", "near", "far"}:
                score = side["left" if m.value in HORIZONTAL else "top" if m.value in VERTICAL else "near"]
                vals = [score(r) for r in rows]
                best = max(vals) if m.value in ("left", "top", "near") else min(vals)
                rows = [r for r, v in zip(rows, vals) if abs(v - best) < 0.5]
            elif rows and m.kind == "ordinal":
                order, n = sorted(rows, key=near), int(m.value)
                rows = [order[n - 1 if n > 0 else n]] if abs(n) <= len(order) else []
        if not rows:
            names = ", ".join(f"{r[0].id}..{r[-1].id}" for r in (spatial.rows(spots) if spots else []))
            raise GroundingError(f"no {np.full() or 'row'} here; rows of spots: {names or 'none'}")
        return rows

    def _relation(self, objs, m: Modifier, np):
        marks = [self.choice((lm,), None) for lm in m.landmarks]
        if m.value == "between":
            kept = [o for o in objs if any(relations.between(o, a, b) for a in marks[0] for b in marks[1])]
        else:
            kept = [o for o in objs if any(relations.holds(m.value, o, lm, self.scene) for lm in marks[0])]
        if kept or m.negated:
            return kept, {}
        if m.value == "next_to":  # the declared relaxation: nothing within reach -> the nearest, within twice the reach
            gaps = {o.id: g for o in objs if (g := relations.nearest_gap(o, marks[0])) is not None}
            if gaps:
                best = min(gaps.values())
                kept = [o for o in objs if o.id in gaps and gaps[o.id] <= best + relations.TIE]
                self.notes.append(f"nothing is within reach {m.word} {m.landmark.full()}; kept the nearest: "
                                  + ", ".join(f"{o.id} ({gaps[o.id]:.2f} m away)" for o in kept))
                return kept, {}
        near = sorted((o for o in objs if o.id not in {x.id for g in marks for x in g}),
                      key=lambda o: min(relations.gap(o, x) for g in marks for x in g))
        closest = ", ".join(f"{o.id} ({min(relations.gap(o, x) for g in marks for x in g):.2f} m away)" for o in near[:3])
        said = f"{m.word} {' and '.join(lm.full() for lm in m.landmarks)}"
        raise GroundingError(f"no {np.describe() or 'object'} {said}; the nearest: {closest or 'none'}")

    def _colour(self, objs, m: Modifier, np):
        labels = {o.id: self.colour(o) or "unknown colour" for o in objs}
        return [o for o in objs if labels[o.id] == m.value], labels

    def _attribute(self, objs, m: Modifier, np):
        if not np.head and not any(m.word in _values(o) for o in self.scene.objects):  # "pick up the widget"
            raise GroundingError(f"unknown word {m.word!r}{self.lexicon.hint(m.word)}; objects here: {inventory(self.scene)}; verbs: {verb_list(self.lexicon)}")
        if not any(m.word in _values(o) for o in self.scene.objects):
            raise GroundingError(f"unknown word {m.word!r}: not a colour, size or position, and no object here has it as an attribute{self.lexicon.hint(m.word)}")
        return [o for o in objs if m.word in _values(o)], {o.id: f"not {m.word!r}" for o in objs}

    def _size(self, objs, m: Modifier, np):
        labels = {o.id: self.size_class(o) for o in objs}
        if not any(labels.values()):
            self.notes.append(f"{m.word!r} ignored: the {_plural_word(np, objs)} here are all about the same size")
            return None, {}
        return [o for o in objs if labels[o.id] == m.value], {k: v or "unknown size" for k, v in labels.items()}

    def _position(self, objs, m: Modifier, np):
        labels = self.positions(objs)
        if not any(labels[o.id] & DIMENSION[m.value] for o in objs):
            self.notes.append(f"{m.word!r} ignored: the {_plural_word(np, objs)} cannot be told apart by position")
            return None, {}
        return [o for o in objs if m.value in labels[o.id]], {k: "/".join(sorted(v)) or "unplaced" for k, v in labels.items()}

    def _superlative(self, objs, m: Modifier, np):
        if m.value in ("near", "far"):
            values, tol = self.distances(objs, m.landmark), 0.01
            return [o for o in objs if o.id in spatial.extremes(values, m.value == "far", tol)], {}
        if m.value in ("small", "large"):
            values = {o.id: o.geometry.volume() for o in objs}
            tol = 0.01 * max(values.values())
        elif m.value in HORIZONTAL:
            values, tol = {o.id: spatial.lateral(o, self.scene) for o in objs}, 0.01
        else:
            values, tol = {o.id: spatial.top_height(o) for o in objs}, 0.01
        best = spatial.extremes(values, m.value in ("large", "left", "top"), tol)
        return [o for o in objs if o.id in best], {}

    def _ordinal(self, objs, m: Modifier, np):
        n = int(m.value)
        if n > len(objs) or (all(self.has_role(o.type, "park") for o in objs) and not m.order
                             and n > max(len(r) for r in spatial.rows(objs))):
            raise GroundingError(f"no {np.describe()}: there {'is' if len(objs) == 1 else 'are'} only {len(objs)} "
                                 f"{_plural_word(np, objs) if len(objs) > 1 else np.word or objs[0].type}")
        if not m.order and all(self.has_role(o.type, "park") for o in objs):  # spots count along their row
            rows = [self._from_near_end(r) for r in spatial.rows(objs)]
            return [r[n - 1 if n > 0 else n] for r in rows if n <= len(r)], {}
        ordered = self._ordered(objs, m.order)
        return [ordered[n - 1 if n > 0 else n]], {}

    def _from_near_end(self, row: list[SceneObject]) -> list[SceneObject]:
        """A row (``spatial.rows`` order) counted from its end nearer the robot."""
        d = self.distances([row[0], row[-1]], None)
        return row if d[row[0].id] <= d[row[-1].id] else row[::-1]

    def _ordered(self, objs: list[SceneObject], side: str) -> list[SceneObject]:
        """Objects counted from a side ("from the left": most left first), or in scene-file order."""
        if side in HORIZONTAL:
            return sorted(objs, key=lambda o: spatial.lateral(o, self.scene), reverse=side == "left")
        if side in VERTICAL:
            return sorted(objs, key=spatial.top_height, reverse=side == "top")
        if side == "near":
            d = self.distances(objs, None)
            return sorted(objs, key=lambda o: d[o.id])
        return objs

    # -- facts about objects -----------------------------------------------------------------

    def support(self, obj: SceneObject) -> str | None:
        if obj.id not in self._support:
            self._support[obj.id] = spatial.support_of(obj, self.scene)
        return self._support[obj.id]

    def distances(self, objs: list[SceneObject], landmark: NounPhrase | None) -> dict[str, float]:
        """Distance of each object from the robot's base, or from the nearest object ``landmark`` names."""
        if landmark is None:
            return {o.id: spatial.distance_to_point(o, spatial.robot_position(self.scene)) for o in objs}
        marks = self.choice((landmark,), None)
        return {o.id: min((spatial.distance_between(o, m) for m in marks if m.id != o.id), default=math.inf) for o in objs}

    def name(self, object_id: str) -> str:
        """Words that name an object in a request: "the table", "the middle shelf", else its id."""
        if object_id == spatial.FLOOR:
            return "the floor"
        obj = self.scene.object(object_id)
        noun = obj.type.replace("_", " ")
        peers = self.scene.objects_of_type(obj.type)
        if len(peers) == 1:
            return f"the {noun}"
        words = sorted(self.positions(peers)[obj.id], key=lambda w: w not in VERTICAL | {"middle"})
        return f"the {' '.join(words)} {noun}" if words else obj.id

    def colour(self, obj: SceneObject) -> str | None:
        if not obj.color:
            return None
        c = obj.color.strip().lower()
        return self.lexicon.canonical("colours", c) or c

    def size_class(self, obj: SceneObject) -> str | None:
        if obj.size:
            s = obj.size.strip().lower()
            return self.lexicon.canonical("sizes", s) or s
        peers = {o.id: math.log(o.geometry.volume()) for o in self.scene.objects_of_type(obj.type)}
        classes = spatial.thirds(peers, math.log(spatial.VOLUME_SPREAD))
        return THIRDS[classes[obj.id]][2] if classes else None

    def positions(self, objs: list[SceneObject]) -> dict[str, set[str]]:
        """Position words that fit each object: {"top", "left", ...} (see grounding.spatial)."""
        out = {o.id: set() for o in objs}
        furniture = [o for o in objs if self.has_role(o.type, "support")]
        for type_name in {o.type for o in furniture}:
            groups = spatial.units(self.scene.objects_of_type(type_name))
            side = spatial.thirds({str(i): sum(spatial.lateral(o, self.scene) for o in g) / len(g) for i, g in enumerate(groups)}, spatial.SPREAD)
            for i, g in enumerate(groups):
                heights = {o.id: spatial.top_height(o) for o in g}
                top, bottom = spatial.extremes(heights, True, 0.01), spatial.extremes(heights, False, 0.01)
                for o in g:
                    if o.id in out:
                        out[o.id] |= {w for w, ok in (("top", o.id in top), ("bottom", o.id in bottom)) if ok} or {"middle"}
                        if side:
                            out[o.id].add(THIRDS[side[str(i)]][1])
        others = [o for o in objs if not self.has_role(o.type, "support")]
        vertical = spatial.thirds({o.id: spatial.top_height(o) for o in others}, spatial.SPREAD)
        horizontal = spatial.thirds({o.id: spatial.lateral(o, self.scene) for o in others}, spatial.SPREAD)
        for o in others:
            if vertical:
                out[o.id].add(THIRDS[vertical[o.id]][0])
            if horizontal:
                word = THIRDS[horizontal[o.id]][1]
                if word != "middle" or not vertical:  # "middle" means the middle height when heights differ
                    out[o.id].add(word)
        for o in objs:  # explicit scene data wins
            for key, words in (("level", ("top", "middle", "bottom")), ("side", ("left", "middle", "right"))):
                given = str(o.attributes.get(key, "")).lower()
                if given in words:
                    out[o.id] = (out[o.id] - set(words)) | {given}
        return out

    def _nothing(self, np: NounPhrase, applied: list[tuple[str, str]], objs: list[SceneObject], labels: dict[str, str], arg=None) -> str:
        """"no red can on the table; cans on the table are: blue x2" (the words applied so far as context)."""
        counts = Counter(labels[o.id] for o in objs)
        breakdown = ", ".join(f"{k} x{n}" for k, n in counts.items())
        adjectives = [w for kind, w in applied if kind != "location"] + [_plural_word(np, objs)]
        where = " ".join(w for kind, w in applied if kind == "location") or "here"
        said = np.describe()
        if np.head not in ("noun", "id"):  # "no middle" -> "no middle parking spot"
            types = {o.type for o in objs}
            said = f"{np.text} {types.pop().replace('_', ' ') if len(types) == 1 else 'object'}{said[len(np.text):]}".strip()
        if isinstance(arg, Modifier) and arg.negated:
            said = f"{said} that is not {arg.word}"
        return f"no {said}; {' '.join(adjectives)} {where} are: {breakdown}"


def _said(kind: str, arg) -> str:
    if kind == "location":
        return f"{'not ' if arg.negated else ''}{arg.prep} {' or '.join(a.full() for a in arg.alternatives)}"
    return arg.word


def _ids(objs: list[SceneObject]) -> str:
    return ", ".join(o.id for o in objs[:8]) + (", ..." if len(objs) > 8 else "")


def _id_pieces(text: str) -> list[str]:
    return re.findall(r"[a-z]+|[0-9]+", text.lower())


def _id_ends_with(object_id: str, tail: str) -> bool:
    """Whether an id ends with what was said: "spot_b1" ends with "b1" and "1"; numbers compare as numbers ("04" = "4")."""
    ids, said = _id_pieces(object_id), _id_pieces(tail)
    if len(said) > len(ids) or not said:
        return False
    return all(a == b or (a.isdigit() and b.isdigit() and int(a) == int(b)) for a, b in zip(ids[-len(said):], said))


def _id_number(object_id: str) -> int | None:
    """The trailing number of an id (spot_b12 -> 12), for ranges."""
    m = re.search(r"([0-9]+)\D*$", object_id)
    return int(m.group(1)) if m else None


def _plural_word(np: NounPhrase, objs: list[SceneObject]) -> str:
    if np.head == "noun":
        return np.word if np.plural else plural(np.word)
    types = {o.type for o in objs}
    return plural(types.pop().replace("_", " ")) if len(types) == 1 else "objects"


def _values(obj: SceneObject) -> set[str]:
    """Words an attribute adjective can match: the colour and attribute values."""
    vals = {str(v).lower() for v in obj.attributes.values()} | ({obj.color.lower()} if obj.color else set())
    return vals | {w for v in vals for w in v.replace("_", " ").split()}
