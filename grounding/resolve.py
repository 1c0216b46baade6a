"""Noun phrases -> the scene objects they can mean, with errors that say which word found nothing.

Filters apply in a fixed order — location, colour, attribute, size, position,
superlative, ordinal — each to what the previous ones kept, so a message can say "no red
can on the table; cans on the table are: blue x2". Sizes compare an object with
all objects of its type (a small box stays small wherever it is); positions of
furniture compare whole units; other positions compare the objects still in
play ("the left can on the table" is the left one of the cans on the table).
Explicit scene data wins over geometry: ``size``, ``attributes.level``
(top/middle/bottom) and ``attributes.side`` (left/middle/right).
"""

from __future__ import annotations

import math
from collections import Counter

from grounding import spatial
from grounding.lexicon import Lexicon, plural
from grounding.model import GroundingError
from grounding.parse import Modifier, NounPhrase
from grounding.regions import type_definitions
from lazyground.scene.schema import Scene, SceneObject

ROLE_VERB = {"pick": "pick up", "support": "put things on", "park": "park in", None: "find"}
ORDER = {"colour": 1, "attribute": 2, "size": 3, "position": 4, "superlative": 5, "ordinal": 6, "state": 0}
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
        objs = self._base(np, role)
        applied: list[str] = []
        steps = [("location", loc) for loc in np.locations] + [(m.kind, m) for m in sorted(np.modifiers, key=lambda m: ORDER[m.kind])]
        for kind, arg in steps:
            if kind == "state":
                continue
            kept, labels = getattr(self, f"_{kind}")(objs, arg, np)
            if kept is None:
                continue
            if not kept:
                raise GroundingError(self._nothing(np, applied, objs, labels))
            objs = kept
            applied.append((kind, f"{arg[0]} {' or '.join(a.full() for a in arg[1])}" if kind == "location" else arg.word))
        return objs

    # -- the objects a head can name -------------------------------------------------------

    def _base(self, np: NounPhrase, role: str | None) -> list[SceneObject]:
        verb = ROLE_VERB[role]
        if np.head in ("robot", "pronoun"):
            raise GroundingError(f"cannot {verb} {np.word!r}: that is the robot")
        if np.head == "floor":
            raise GroundingError(f"cannot {verb} the {np.word}")
        if np.head == "id":
            objs = [self.scene.object(np.value)]
        elif np.head == "noun":
            objs = self.scene.objects_of_type(np.value)
            if not objs:
                raise GroundingError(f"no {np.word!r} in this scene; it has: {inventory(self.scene)}")
        else:
            objs = [o for o in self.scene.objects if self.has_role(o.type, role) and (role == "park") == self.has_role(o.type, "park")]
            if not objs and role == "park":
                raise GroundingError(f"no parking spot in this scene; it has: {inventory(self.scene)}")
            if not objs:
                raise GroundingError(f"nothing to {verb} in this scene; it has: {inventory(self.scene)}")
        bad = sorted({o.type for o in objs if not self.has_role(o.type, role)})
        if bad:
            word = np.word or bad[0]
            raise GroundingError(f"cannot {verb} {'an' if word[:1] in 'aeiou' else 'a'} {word}: type {bad[0]!r} has no {role!r} definition in lazyground/scene/types.yaml")
        return self._free(objs, np) if role == "park" else self._ignore_states(objs, np)

    def _free(self, objs: list[SceneObject], np: NounPhrase) -> list[SceneObject]:
        state = next((m for m in np.modifiers if m.kind == "state" and m.value != "free"), None)
        if state is not None:
            raise GroundingError(f"not supported: parking in a spot that is {state.word!r}; occupied spots are never goals")
        free = [o for o in objs if not o.occupied]
        if free:
            return free
        if np.head == "id":
            others = [o.id for o in self.scene.objects_of_type(objs[0].type) if not o.occupied]
            raise GroundingError(f"{objs[0].id} is occupied; free ones: {', '.join(others) or 'none'}")
        raise GroundingError(f"no free {np.word or 'parking spot'} here: all {len(objs)} are occupied")

    def _ignore_states(self, objs: list[SceneObject], np: NounPhrase) -> list[SceneObject]:
        for m in np.modifiers:
            if m.kind == "state":
                self.notes.append(f"{m.word!r} ignored: it only describes parking spots")
        return objs

    # -- filters: each returns (kept or None = does not narrow, {id: label} for messages) --

    def _location(self, objs, loc, np):
        prep, alts = loc
        landmarks = set()
        for alt in alts:
            landmarks |= {spatial.FLOOR} if alt.head == "floor" else {o.id for o in self.choice((alt,), None)}
        labels = {o.id: self.support(o) for o in objs}
        kept = [o for o in objs if labels[o.id] in landmarks]
        return kept, {k: f"on {self.name(v)}" if v else "not on a surface" for k, v in labels.items()}

    def _colour(self, objs, m: Modifier, np):
        labels = {o.id: self.colour(o) or "unknown colour" for o in objs}
        return [o for o in objs if labels[o.id] == m.value], labels

    def _attribute(self, objs, m: Modifier, np):
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
        if n > len(objs):
            raise GroundingError(f"no {np.describe()}: there {'is' if len(objs) == 1 else 'are'} only {len(objs)} "
                                 f"{_plural_word(np, objs) if len(objs) > 1 else np.word or objs[0].type}")
        return [objs[n - 1 if n > 0 else n]], {}

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

    def _nothing(self, np: NounPhrase, applied: list[tuple[str, str]], objs: list[SceneObject], labels: dict[str, str]) -> str:
        """"no red can on the table; cans on the table are: blue x2" (the words applied so far as context)."""
        counts = Counter(labels[o.id] for o in objs)
        breakdown = ", ".join(f"{k} x{n}" for k, n in counts.items())
        adjectives = [w for kind, w in applied if kind != "location"] + [_plural_word(np, objs)]
        where = " ".join(w for kind, w in applied if kind == "location") or "here"
        said = np.describe()
        if np.head not in ("noun", "id"):  # "no middle" -> "no middle parking spot"
            types = {o.type for o in objs}
            said = f"{np.text} {types.pop().replace('_', ' ') if len(types) == 1 else 'object'}{said[len(np.text):]}".strip()
        return f"no {said}; {' '.join(adjectives)} {where} are: {breakdown}"


def _plural_word(np: NounPhrase, objs: list[SceneObject]) -> str:
    if np.head == "noun":
        return np.word if np.plural else plural(np.word)
    types = {o.type for o in objs}
    return plural(types.pop().replace("_", " ")) if len(types) == 1 else "objects"


def _values(obj: SceneObject) -> set[str]:
    """Words an attribute adjective can match: the colour and attribute values."""
    vals = {str(v).lower() for v in obj.attributes.values()} | ({obj.color.lower()} if obj.color else set())
    return vals | {w for v in vals for w in v.replace("_", " ").split()}
