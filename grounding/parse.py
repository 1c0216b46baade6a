"""Request text -> phrase structure (no scene geometry here).

Grammar, over the lexicon's categories (polite words, fillers such as "me" and
particles such as "up" are dropped first):

    request  := VERB [choice] pp*
    choice   := np ("or" np)*
    np       := [DET] modifier* [HEAD]          HEAD: noun | object id | wildcard | robot | floor | "one"
    modifier := COLOUR | SIZE | POSITION | SUPERLATIVE | ORDINAL | STATE | unknown-word (a scene attribute value)
    pp       := PREP choice

A noun may be followed by "nearest"/"farthest" [to] np ("the can nearest the
table"): the superlative then measures from that object, not the robot.

A prepositional phrase without a noun that only holds positions ("the can on
the left") joins the phrase before it. "VERB X and put it PP" reads as "put X
PP". Counts above one, "all", "and", negation and pronouns are refused with a
"not supported" line rather than guessed.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from grounding.lexicon import Lexicon, Token, plural
from grounding.model import GroundingError

DROPPED = {"polite", "filler", "particle"}
MODIFIERS = {"colour", "size", "position", "superlative", "ordinal", "state"}
DISTANCES = {"near", "far"}
HEADS = {"noun", "id", "wildcard", "robot", "floor", "pronoun"}
NP_START = MODIFIERS | HEADS | {"determiner", "unknown"}


@dataclass(frozen=True)
class Modifier:
    """A word narrowing a noun: kind (colour, size, position, ...), canonical value, the word typed.

    ``landmark`` is the object a distance superlative measures from ("nearest the table"); None = the robot.
    """

    kind: str
    value: str
    word: str
    landmark: "NounPhrase | None" = None


@dataclass(frozen=True)
class NounPhrase:
    """One noun phrase: ``head`` kind ("noun", "id", "wildcard", "robot", "floor", "pronoun" or "")."""

    text: str  # the words typed, without the determiner
    head: str = ""
    value: str = ""  # object type (noun), object id (id)
    word: str = ""  # the head word typed
    plural: bool = False
    determiner: str = ""  # "definite", "indefinite" or ""
    determiner_word: str = ""
    modifiers: tuple[Modifier, ...] = ()
    locations: tuple[tuple[str, tuple["NounPhrase", ...]], ...] = ()  # (preposition, alternatives)

    @property
    def position_only(self) -> bool:
        return not self.head and bool(self.modifiers) and all(m.kind in ("position", "superlative") for m in self.modifiers)

    def describe(self) -> str:
        """The phrase as typed, with its locations ("red can on the table")."""
        locs = "".join(f" {prep} {' or '.join(a.full() for a in alts)}" for prep, alts in self.locations)
        return f"{self.text}{locs}"

    def full(self) -> str:
        return f"{self.determiner_word} {self.describe()}".strip()


@dataclass(frozen=True)
class Phrase:
    """A parsed request: the verb, the object choice and the prepositional phrases in order."""

    verb: Token
    object: tuple[NounPhrase, ...]
    pps: tuple[tuple[Token, tuple[NounPhrase, ...]], ...]


def verb_list(lexicon: Lexicon) -> str:
    """A short list of verbs for messages ("pick" is left out when "pick up" is shown)."""
    shown = [v for action, n in (("pick", 8), ("place", 4), ("park", 1)) for v in lexicon.verbs(action)[:n]]
    return ", ".join(v for v in shown if not any(o.startswith(v + " ") for o in shown))


def parse(tokens: list[Token], lexicon: Lexicon, things: str) -> Phrase:
    """Parse tokens into a Phrase.

    Args:
        things: what the scene holds ("can x3, box x2"), for messages about unknown nouns.

    Raises:
        GroundingError: one line naming the unknown word or the unsupported form.
    """
    toks = [t for t in tokens if t.cat not in DROPPED]
    if not toks:
        raise GroundingError("empty request: say what to do, e.g. 'pick up a can', 'put a cup on the table' or 'park'")
    toks = _splice_put_it(toks)
    verb = toks[0]
    if verb.cat != "verb":
        hint = f"unknown word {verb.text!r}{lexicon.hint(verb.text, 'verb')}" if verb.cat == "unknown" else f"a request starts with a verb, not {verb.text!r}"
        raise GroundingError(f"{hint}; supported verbs: {verb_list(lexicon)} (see docs/requests.md)")
    _refuse_unsupported(toks, lexicon, parking=verb.value == "park")
    cur = _Cursor(toks[1:], lexicon, things)
    obj = cur.choice()
    pps = []
    while cur.peek is not None and cur.peek.cat == "preposition":
        prep = cur.take()
        alts = cur.choice()
        if not alts:
            raise GroundingError(f"expected an object after {prep.text!r}, e.g. '{prep.text} the table'")
        pps.append((prep, alts))
    if cur.peek is not None:
        raise cur.unexpected(cur.peek)
    return _attach_positions(Phrase(verb, obj, tuple(pps)))


def _splice_put_it(toks: list[Token]) -> list[Token]:
    """"grab X and put it on Y" -> "put X on Y"."""
    for i, t in enumerate(toks[:-2]):
        nxt, pron = toks[i + 1], toks[i + 2]
        if (t.cat == "conjunction" and i > 0 and toks[0].cat == "verb" and toks[0].value == "pick"
                and nxt.cat == "verb" and nxt.value == "place" and pron.cat == "pronoun"):
            return [nxt] + toks[1:i] + toks[i + 3:]
    return toks


def _refuse_unsupported(toks: list[Token], lexicon: Lexicon, parking: bool) -> None:
    for i, t in enumerate(toks):
        if t.cat == "multiple" and t.text.isdigit() and i > 0 and toks[i - 1].cat == "noun":  # "can 7": an id, not a count
            said = f"{toks[i - 1].text} {t.text}"
            raise GroundingError(f"no {said!r} in this scene{lexicon.ids_with(toks[i - 1].text)}")
        if t.cat == "negation":
            raise GroundingError(f"not supported: negation ({t.text!r}); describe the object you want instead, e.g. 'the red can'")
        if t.cat == "multiple":
            phrase = " ".join(x.text for x in toks[i:_next_head(toks, i) + 1])
            noun = next((x for x in toks[i:] if x.cat == "noun"), None)
            example = f" (try 'one of the {plural(noun.text) if not noun.entry.plural else noun.text}')" if noun else ""
            raise GroundingError(f"not supported: {phrase!r} asks for several objects; the robot handles one at a time{example}")
        if t.cat == "conjunction":
            raise GroundingError(f"not supported: {t.text!r} joins two objects or actions; ask for one at a time")
        if t.cat == "pronoun" and not parking:
            raise GroundingError(f"not supported: {t.text!r} (nothing to refer back to); name the object, e.g. 'pick up the can'")


def _next_head(toks: list[Token], i: int) -> int:
    for j in range(i, len(toks)):
        if toks[j].cat in HEADS:
            return j
    return i


class _Cursor:
    """A read position over the tokens after the verb."""

    def __init__(self, toks: list[Token], lexicon: Lexicon, things: str):
        self.toks, self.i, self.lexicon, self.things = toks, 0, lexicon, things

    @property
    def peek(self) -> Token | None:
        return self.toks[self.i] if self.i < len(self.toks) else None

    def ahead(self, k: int) -> Token | None:
        return self.toks[self.i + k] if self.i + k < len(self.toks) else None

    def take(self) -> Token:
        self.i += 1
        return self.toks[self.i - 1]

    def unexpected(self, t: Token) -> GroundingError:
        if t.cat == "unknown":
            return GroundingError(f"unknown word {t.text!r}{self.lexicon.hint(t.text)}; objects here: {self.things}; verbs: {verb_list(self.lexicon)}")
        if t.cat == "verb":
            return GroundingError(f"not supported: a second verb {t.text!r}; ask for one action at a time")
        return GroundingError(f"unexpected {t.text!r} after '{' '.join(x.text for x in self.toks[:self.i])}'")

    def choice(self) -> tuple[NounPhrase, ...]:
        first = self.np()
        if first is None:
            return ()
        alts = [first]
        while self.peek is not None and self.peek.cat == "disjunction":
            word = self.take().text
            nxt = self.np()
            if nxt is None:
                raise GroundingError(f"expected an object after {word!r}")
            alts.append(nxt)
        return tuple(alts)

    def np(self) -> NounPhrase | None:
        t = self.peek
        if t is None or t.cat not in NP_START:
            return None
        start = self.i
        det = self.take() if t.cat == "determiner" else None
        mods = []
        while self.peek is not None:
            t = self.peek
            if t.cat in MODIFIERS:
                mods.append(Modifier(t.cat, t.value, self.take().text))
            elif t.cat == "unknown" and self.ahead(1) is not None and _continues(self.ahead(1)):
                mods.append(Modifier("attribute", t.text, self.take().text))
            else:
                break
        head = self.peek
        if head is not None and (head.cat in HEADS or (head.cat == "determiner" and head.text == "one" and (det or mods))):
            self.take()
            kind = "wildcard" if head.cat == "determiner" else head.cat
            np = NounPhrase("", kind, head.value, head.text, bool(head.entry.plural))
        elif head is not None and head.cat == "unknown":
            raise self.unexpected(head)
        else:
            np = NounPhrase("")
        if np.head and self.peek is not None and self.peek.cat == "superlative" and self.peek.value in DISTANCES:
            mods.append(self._distance())
        if det is None and not mods and not np.head:
            return None
        if not mods and not np.head:  # "pick up the": a dangling article must not mean "anything"
            raise GroundingError(f"expected an object after {det.text!r}")
        text = " ".join(x.text for x in self.toks[start + (det is not None):self.i])
        return replace(np, text=text, determiner=det.value if det else "", determiner_word=det.text if det else "",
                       modifiers=tuple(mods))

    def _distance(self) -> Modifier:
        """ "nearest [to] the table" after a noun: the superlative and the object it measures from."""
        word = self.take()
        if self.peek is not None and self.peek.cat == "preposition" and self.peek.text == "to":
            self.take()
        landmark = self.np()
        return Modifier("superlative", word.value, word.text, landmark)


def _continues(t: Token) -> bool:
    """Whether ``t`` can follow an attribute word inside a noun phrase."""
    return t.cat in MODIFIERS | HEADS or t.cat == "unknown" or (t.cat == "determiner" and t.text == "one")


def _attach_positions(p: Phrase) -> Phrase:
    """Noun-less position phrases ("on the left") narrow the phrase just before them."""
    groups: list[list] = [list(p.object)]
    preps: list[Token] = []
    for prep, alts in p.pps:
        if all(a.position_only for a in alts) and groups[-1]:
            mods = tuple(m for a in alts for m in a.modifiers)
            said = " or ".join(a.full() for a in alts)
            groups[-1] = [replace(a, modifiers=a.modifiers + mods, text=f"{a.text} {prep.text} {said}".strip()) for a in groups[-1]]
        else:
            groups.append(list(alts))
            preps.append(prep)
    return Phrase(p.verb, tuple(groups[0]), tuple(zip(preps, (tuple(g) for g in groups[1:]))))
