"""The semantic result of parsing a request: clauses, noun phrases and their modifiers (no scene here).

``grounding.parse.parse`` builds these from the grammar (grounding/grammar.lark), one rule per
construction; ``grounding.resolve`` maps a ``NounPhrase`` to scene objects. A noun phrase carries
its ``Quantity`` ("a can" one, "two cans" n=2, "all the cups" all, "each box" each) and a clause
its conjoined objects ("a cup and a box"), so that several-object requests are represented even
where today's grounding refuses them.
"""

from __future__ import annotations

from dataclasses import dataclass

from grounding.lexicon import Token


@dataclass(frozen=True)
class Quantity:
    """How many objects a noun phrase asks for.

    ``kind``: "one" ("a can", "the can", "one of the cans"), "n" ("two cans", "the 3 boxes"; ``count``),
    "all" ("all the cups", "the cans", "every box", "both cans": ``count`` 2), "each" ("each can"),
    "some" ("some cans", "a few boxes": ``count`` None).
    """

    kind: str = "one"
    count: int | None = 1
    word: str = ""

    @property
    def single(self) -> bool:
        return self.kind == "one"


@dataclass(frozen=True)
class Modifier:
    """A word or phrase narrowing a noun: kind, canonical value, the words typed.

    kinds: colour, attribute, size, position, superlative, ordinal, state, relation.
    ``landmarks``: what a relation or a distance superlative measures from ("next to the box",
    "between X and Y"; none = the robot). ``negated``: "not red", "not next to the box".
    ``order``: for ordinals, the side counted from ("left", "right", "top", "bottom", "near"), "" = scene-file order.
    """

    kind: str
    value: str
    word: str
    landmarks: tuple["NounPhrase", ...] = ()
    negated: bool = False
    order: str = ""

    @property
    def landmark(self) -> "NounPhrase | None":
        return self.landmarks[0] if self.landmarks else None


@dataclass(frozen=True)
class Location:
    """A support phrase ("on the table", "from the top shelf"), possibly negated ("not on the table")."""

    prep: str
    alternatives: tuple["NounPhrase", ...]
    negated: bool = False


@dataclass(frozen=True)
class NounPhrase:
    """One noun phrase. ``head``: "noun", "id", "idref", "wildcard", "robot", "person", "floor", "pronoun" or "".

    ``value`` is the object type (noun, idref) or the object id (id); ``tails`` the id endings an idref
    names ("spot 3 or 4": ("3", "4")), ``id_range`` a numeric range ("spots 3 to 6"). ``excluded``
    are the phrases "except ..." / "but ..." / "not ..." subtract; ``free`` marks a free-choice word
    ("anywhere", "whichever", "any of them") and ``different`` "a different / another cup".
    """

    text: str
    head: str = ""
    value: str = ""
    word: str = ""
    plural: bool = False
    determiner: str = ""  # "definite", "indefinite" or ""
    determiner_word: str = ""
    quantity: Quantity = Quantity()
    modifiers: tuple[Modifier, ...] = ()
    locations: tuple[Location, ...] = ()
    excluded: tuple["NounPhrase", ...] = ()
    tails: tuple[str, ...] = ()
    id_range: tuple[int, int] | None = None
    free: bool = False
    different: bool = False

    @property
    def position_only(self) -> bool:
        return (not self.head and bool(self.modifiers) and not self.locations
                and all(m.kind in ("position", "superlative") and not m.landmarks for m in self.modifiers))

    def describe(self) -> str:
        """The phrase as typed, with its locations ("red can on the table")."""
        locs = "".join(f" {'not ' if loc.negated else ''}{loc.prep} {' or '.join(a.full() for a in loc.alternatives)}"
                       for loc in self.locations)
        return f"{self.text}{locs}"

    def full(self) -> str:
        return f"{self.determiner_word} {self.describe()}".strip()


@dataclass(frozen=True)
class PrepPhrase:
    """A clause-level prepositional phrase: the preposition token and the alternatives it names."""

    prep: Token
    alternatives: tuple[NounPhrase, ...]


@dataclass(frozen=True)
class Clause:
    """One verb with its objects and prepositional phrases.

    ``objects`` is a conjunction ("a cup and a box") of choices ("the can or the cup"): one tuple of
    alternatives per conjunct. ``manner`` is a parking direction ("reversing", "forwards", "").
    ``negated``: "don't pick up ...". ``to_person``: "bring it to me" (the robot carries it).
    """

    verb: Token
    objects: tuple[tuple[NounPhrase, ...], ...] = ()
    pps: tuple[PrepPhrase, ...] = ()
    manner: str = ""
    negated: bool = False
    to_person: bool = False
    free_target: bool = False  # "put it anywhere", "park the car somewhere"
    conjunction: str = ""  # the word joining several objects ("and", "with"), for messages

    @property
    def object(self) -> tuple[NounPhrase, ...]:
        """The first (today the only) object choice; () when the clause names none."""
        return self.objects[0] if self.objects else ()


@dataclass(frozen=True)
class Request:
    """A parsed request: its clauses joined by "and" / "then" ("find a spot and park")."""

    clauses: tuple[Clause, ...]
    conjunction: str = ""  # the word joining the clauses ("and", "then")
