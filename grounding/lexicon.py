"""The word table (``lexicon.yaml``) as a phrase index, and the tokenizer that uses it.

``Lexicon.for_scene(scene)`` adds the scene's object types and ids as nouns;
``Lexicon.tokens(text)`` splits a request into the longest known phrases.
"""

from __future__ import annotations

import difflib
import os
import re
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path

import yaml

from grounding.model import GroundingError
from lazyground.scene.schema import Scene
from lazyground.typed_yaml import load_yaml

LEXICON_FILE = Path(__file__).with_name("lexicon.yaml")
ENV_VAR = "LAZYGROUND_LEXICON"
WORD = re.compile(r"[a-z0-9_]+(?:'[a-z]+)?")

# section -> category for the flat word lists; mapping sections are handled below
FLAT = {
    "robot": "robot", "person": "person", "floor": "floor", "wildcards": "wildcard", "one": "one", "free": "free",
    "number_marks": "number_mark", "coloured": "coloured", "between": "between", "through": "through",
    "relativizers": "which", "participles": "participle", "negations": "negation", "exceptions": "exception",
    "but": "but", "different": "different", "polite": "polite", "fillers": "filler", "particles": "particle",
    "conjunctions": "conjunction", "disjunctions": "disjunction", "pronouns": "pronoun", "layout": "layout", "rows": "row",
}
# section -> category for "value: [phrases]" sections
MAPPED = {
    "verbs": "verb", "manners": "manner", "nouns": "noun", "determiners": "determiner", "quantifiers": "quantifier",
    "numbers": "number", "colours": "colour", "sizes": "size", "positions": "position", "superlatives": "superlative",
    "states": "state", "prepositions": "preposition", "ordinals": "ordinal", "relations": "relation",
    "distances": "distance",
}
# "no. 3", "#3", "nr 3" -> "number 3" (so "no" stays a plain word elsewhere)
NUMBER_SIGN = re.compile(r"(?:#|\bno\.?|\bnr\.?|\bnum\.?)\s*(?=\d)")
SIDES = {"left", "right", "top", "bottom"}
IDTAIL = re.compile(r"[a-z]{0,3}[0-9]+[a-z]?")
SPLIT = re.compile(r"[a-z]+|[0-9]+")


@dataclass(frozen=True)
class Entry:
    """What a phrase means: a category (verb, noun, colour, ...) and a canonical value."""

    cat: str
    value: str = ""
    plural: bool = False


@dataclass(frozen=True)
class Token:
    """One matched phrase of a request; ``entry`` is None for an unknown word."""

    text: str
    entry: Entry | None

    @property
    def cat(self) -> str:
        return self.entry.cat if self.entry else "unknown"

    @property
    def value(self) -> str:
        return self.entry.value if self.entry else self.text


@dataclass(frozen=True)
class Lexicon:
    """A phrase index: word tuples -> Entry, plus the raw tables for messages."""

    phrases: dict = field(default_factory=dict)
    data: dict = field(default_factory=dict)
    _scenes: dict = field(default_factory=dict, repr=False, compare=False)  # (types, ids) -> for_scene's lexicon

    @property
    def max_len(self) -> int:
        return max((len(p) for p in self.phrases), default=1)

    def verbs(self, action: str) -> list[str]:
        return list(self.data.get("verbs", {}).get(action, []))

    def canonical(self, section: str, word: str) -> str | None:
        """The canonical value of ``word`` in a mapped section (e.g. colours: grey -> gray)."""
        for value, words in self.data.get(section, {}).items():
            if word == value or word in words:
                return value
        return None

    def for_scene(self, scene: Scene) -> "Lexicon":
        """This lexicon plus the scene's types (as nouns) and object ids; lexicon words win clashes (made once per
        set of objects' types and ids: #33, 4 ms of a 256-spot lot's request)."""
        key = tuple((obj.type, obj.id) for obj in scene.objects)
        if key not in self._scenes:
            if len(self._scenes) >= 64:
                self._scenes.clear()
            self._scenes[key] = self._for_objects(scene)
        return self._scenes[key]

    def _for_objects(self, scene: Scene) -> "Lexicon":
        phrases = dict(self.phrases)
        for obj in scene.objects:
            words = tuple(WORD.findall(obj.type.lower().replace("_", " ")))
            if words and words not in phrases:
                _add_noun(phrases, words, obj.type)
            key = tuple(WORD.findall(obj.id.lower()))
            if key and key not in phrases:
                phrases[key] = Entry("id", obj.id)
        # "can 2" and "spot b1" name Can2 and spot_b1; a spelling two ids share names neither
        spelt: dict[tuple, set[str]] = {}
        for obj in scene.objects:
            for key in id_spellings(obj.id):
                spelt.setdefault(key, set()).add(obj.id)
        for key, ids in spelt.items():
            if len(ids) == 1 and key not in phrases:
                phrases[key] = Entry("id", ids.pop())
        return Lexicon(phrases, self.data)

    def hint(self, word: str, cat: str | None = None, only: bool = False) -> str:
        """"; did you mean 'pick'?" and "; ids with 'b1': spot_b1, ..." for an unknown word ("" if none).

        Args:
            cat: a category the word should have had (e.g. "verb"): its words are suggested first.
            only: suggest words of ``cat`` only (a verb's place: "throw" is no typo of "row").
        """
        close: list[str] = []
        for want in ((cat,) if cat else ()) + (() if only and cat else (None,)):  # ids are listed by ids_with, not guessed at
            known = sorted({key[0] for key, e in self.phrases.items() if e.cat != "id" and want in (None, e.cat)
                            and len(key) == 1 and not key[0].isdigit() and key[0] != word})  # words said alone
            swapped = [w for w in known if sorted(w) == sorted(word)]  # "pikc", "cna": two letters swapped
            near = [w for w in difflib.get_close_matches(word, known, n=3, cutoff=0.75)
                    if w not in swapped and abs(len(w) - len(word)) <= 2]  # a typo, not a longer or shorter word
            close = close or (swapped + near)[:3]
        out = f"; did you mean {' or '.join(repr(w) for w in close)}?" if close else ""
        return out + self.ids_with(word)

    def ids_with(self, word: str) -> str:
        """"; ids with 'b1': spot_b1, spot_b10" when ``word`` is part of scene ids ("" if none)."""
        ids = sorted({e.value for e in self.phrases.values() if e.cat == "id" and word in e.value.lower() and word != e.value.lower()})
        return f"; ids with {word!r}: {', '.join(ids[:6])}{', ...' if len(ids) > 6 else ''}" if ids else ""

    def tokens(self, text: str) -> list[Token]:
        """Greedy longest-phrase segmentation of lower-cased ``text``."""
        words = WORD.findall(NUMBER_SIGN.sub(" number ", text.lower()))
        out, i, n = [], 0, self.max_len
        while i < len(words):
            # "from the right next to ...": after "from (the)", a side word stands alone ("right", not "right next to")
            side = words[i] in SIDES and (words[i - 1:i] == ["from"] or words[max(i - 2, 0):i] == ["from", "the"])
            for k in range(1 if side else min(n, len(words) - i), 0, -1):
                entry = self.phrases.get(tuple(words[i:i + k]))
                if entry is not None:
                    out.append(Token(" ".join(words[i:i + k]), entry))
                    i += k
                    break
            else:
                out.append(Token(words[i], _number(words[i])))
                i += 1
        return out


def id_spellings(object_id: str) -> set[tuple[str, ...]]:
    """Other ways to type an id: split at underscores ("spot b1"), and between letters and digits ("can 2")."""
    low = object_id.lower()
    parts = tuple(p for p in low.split("_") if p)
    pieces = tuple(SPLIT.findall(low))
    return {k for k in (parts, pieces) if k and k != (low,)}


def _number(word: str) -> Entry | None:
    """Digits are numbers (a count before a noun, an id after it); "b1", "12a" are id tails ("park at b1")."""
    if word.isdigit():
        return Entry("number", str(int(word)))
    if IDTAIL.fullmatch(word):
        return Entry("idtail", word)
    return None


def plural(word: str) -> str:
    """English plural of the last word of a phrase (regular rules only)."""
    head, _, last = word.rpartition(" ")
    if re.search(r"(s|x|z|ch|sh)$", last):
        last += "es"
    elif re.search(r"[^aeiou]y$", last):
        last = last[:-1] + "ies"
    elif last.endswith("f"):
        last = last[:-1] + "ves"
    else:
        last += "s"
    return f"{head} {last}".strip()


def _key(phrase, source: str) -> tuple[str, ...]:
    if not isinstance(phrase, (str, int)) or isinstance(phrase, bool):
        raise ValueError(f"{source}: {phrase!r} is not a phrase (quote YAML words such as 'on', 'off', 'no')")
    return tuple(WORD.findall(str(phrase).lower()))


def _add(phrases: dict, words: tuple, entry: Entry, source: str) -> None:
    old = phrases.get(words)
    if old is not None and old != entry:
        raise ValueError(f"lexicon: {' '.join(words)!r} is both {old.cat} {old.value!r} and {entry.cat} {entry.value!r} ({source})")
    phrases[words] = entry


def _add_noun(phrases: dict, words: tuple, type_name: str) -> None:
    phrases.setdefault(words, Entry("noun", type_name))
    phrases.setdefault(tuple(plural(" ".join(words)).split()), Entry("noun", type_name, plural=True))


def build(data: dict, source: str = "lexicon") -> Lexicon:
    """Index the tables of a lexicon mapping (the layout of ``lexicon.yaml``).

    Raises:
        ValueError: a phrase with two meanings, or a malformed section.
    """
    phrases: dict = {}
    for section, cat in FLAT.items():
        for phrase in data.get(section, []) or []:
            _add(phrases, _key(phrase, source), Entry(cat, str(phrase)), source)
    for section, cat in MAPPED.items():
        table = data.get(section, {}) or {}
        if not isinstance(table, dict):
            raise ValueError(f"{source}: {section}: expected a mapping of value -> [phrases]")
        for value, words in table.items():
            for phrase in [value] * (section in ("colours", "sizes", "positions")) + list(words or []):
                key = _key(phrase, source)
                if key:
                    _add(phrases, key, Entry(cat, str(value)), source)
    for plural_word, singular in (data.get("plurals") or {}).items():
        entry = phrases.get(tuple(WORD.findall(str(singular))))
        if entry is None or entry.cat != "noun":
            raise ValueError(f"{source}: plurals: {singular!r} is not a noun")
        phrases[tuple(WORD.findall(str(plural_word)))] = Entry("noun", entry.value, plural=plural_word != singular)
    for value, words in (data.get("nouns") or {}).items():
        for phrase in words or []:
            key = tuple(plural(str(phrase).lower()).split())
            phrases.setdefault(key, Entry("noun", str(value), plural=True))
    return Lexicon(phrases, data)


def merge(base: dict, extra: dict) -> dict:
    """``base`` with ``extra``'s lists appended (mapping sections merged per key)."""
    out = {k: (dict(v) if isinstance(v, dict) else list(v or [])) for k, v in base.items()}
    for key, value in (extra or {}).items():
        if isinstance(value, dict):
            table = out.setdefault(key, {})
            for k, v in value.items():
                table[k] = (list(table.get(k) or []) + list(v or [])) if isinstance(v, list) else v
        else:
            out[key] = list(out.get(key) or []) + list(value or [])
    return out


@lru_cache(maxsize=8)
def _load(paths: tuple[str, ...]) -> Lexicon:
    data = load_yaml(LEXICON_FILE.read_text())  # libyaml: ~0.007 s where PyYAML's parser took ~0.05 s (first request)
    for p in paths:
        try:
            data = merge(data, yaml.safe_load(Path(p).read_text()) or {})
        except (OSError, yaml.YAMLError) as exc:
            raise GroundingError(f"{ENV_VAR}: cannot read {p}: {str(exc).splitlines()[0]}") from None
    return build(data, " + ".join(("lexicon.yaml",) + paths))


def load_lexicon(extra: dict | None = None) -> Lexicon:
    """The bundled lexicon, plus $LAZYGROUND_LEXICON files, plus ``extra`` (same layout)."""
    paths = tuple(p for p in os.environ.get(ENV_VAR, "").split(os.pathsep) if p)
    lex = _load(paths)
    return build(merge(lex.data, extra), "extra") if extra else lex
