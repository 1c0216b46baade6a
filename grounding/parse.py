"""Request text -> clauses and noun phrases (``grounding.phrases``), by the grammar in grammar.lark.

The tokenizer (``Lexicon.tokens``) turns text into lexicon categories; polite words, fillers and
particles are dropped; a LALR(1) parser (lark) builds the one tree and ``_Semantics`` gives each
grammar rule its meaning, one method per rule. LALR rather than Earley: a request has exactly one
parse (the grammar's few shift/reduce choices shift, i.e. a postmodifier joins the phrase it
follows), conflicts show when the grammar is built, and a parse takes well under a millisecond
(Earley over the same grammar took 10-35 ms, more than the whole grounding's budget). Three
words are retagged by their neighbours first, as a person reads them: "and" before a verb joins
clauses (THEN), "or" and "to" between id numbers join ids ("spot 3 or 4", "spots 3 to 6").

A noun-less phrase that only holds positions ("the can on the left") joins the phrase before it.
"""

from __future__ import annotations

import hashlib
import sys
from dataclasses import replace
from functools import lru_cache
from pathlib import Path

import lark
from lark import Lark, Token as LarkToken, Transformer, UnexpectedInput, v_args
from lark.lexer import Lexer

from grounding.lexicon import Entry, Lexicon, Token
from grounding.model import GroundingError
from grounding.phrases import Clause, Location, Modifier, NounPhrase, PrepPhrase, Quantity, Request
from lazyground.user_cache import cache_dir

DROPPED = {"polite", "filler", "particle"}
GRAMMAR = Path(__file__).with_name("grammar.lark")
ORDER_SIDES = {"left", "right", "top", "bottom"}


class _Tokens(Lexer):
    """Feeds pre-tokenized lexicon categories to lark (the token's position indexes the Token list)."""

    def __init__(self, conf):
        pass

    def lex(self, toks):
        for i, t in enumerate(toks):
            yield LarkToken(_terminal(toks, i), t.text, start_pos=i, end_pos=i + 1)


def _terminal(toks: list[Token], i: int) -> str:
    """The grammar terminal of token i: its category, or THEN / IDOR / THROUGH by its neighbours."""
    cat = toks[i].cat
    prev = toks[i - 1].cat if i > 0 else ""
    nxt = toks[i + 1].cat if i + 1 < len(toks) else ""
    after = toks[i + 2].cat if i + 2 < len(toks) else ""
    if cat == "conjunction" and (nxt in ("verb", "manner") or (nxt == "negation" and after == "verb")):
        return "THEN"
    if (toks[i].text == "that" and prev in ("noun", "id", "idtail", "number", "wildcard", "one", "robot", "person", "floor", "position")
            and nxt in ("negation", "participle", "which", "preposition", "relation", "superlative")):
        return "WHICH"  # "a box that isn't red" (but "get me that red mug")
    side = toks[i + 2].cat if nxt == "determiner" and i + 2 < len(toks) else nxt
    if toks[i].text == "from" and side in ("position", "person", "robot") and any(t.cat == "ordinal" for t in toks[:i]):
        return "FROMSIDE"  # "the third can from the left", "the second spot from me"
    if prev == "row" and len(toks[i].text) == 1 and toks[i].text.isalpha():  # "row a", "row c"
        return "IDTAIL"
    ids = ("number", "idtail")
    if cat == "disjunction" and prev in ids and nxt in ids:
        return "IDOR"
    if cat == "preposition" and toks[i].text == "to" and prev == "number" and nxt == "number":
        return "THROUGH"
    return cat.upper()


def _row_name(t: Token) -> bool:
    """A row's name after "row": one letter ("row c") or a number ("row 2")."""
    return (len(t.text) == 1 and t.text.isalpha()) or t.cat == "number"


def _row_per_name(toks: list[Token]) -> list[Token]:
    """ "row t or b" -> "row t or row b": each name joined by "or" to a row's name names a row too."""
    out: list[Token] = []
    for i, t in enumerate(toks):
        if (i >= 2 and toks[i - 1].cat == "disjunction" and _row_name(t) and _row_name(toks[i - 2])
                and any(o.cat == "row" for o in out[-3:-2])):
            out.append(out[-3])
        out.append(t)
    return out


def _cache_file(grammar: str) -> str | bool:
    """Where the built parser is kept between processes: one file per grammar, lark and Python version in the
    user's cache folder (``lazyground.user_cache``: $LAZYGROUND_CACHE/grammar); False (no cache) if it cannot be made.

    Building the LALR tables takes ~0.1-0.2 s of CPU, the first request of every process; loading them ~0.01 s.
    lark checks the file's grammar hash before using it and rebuilds on any unreadable or stale file.
    """
    try:
        root = cache_dir("grammar")
        root.mkdir(parents=True, exist_ok=True)
    except (OSError, RuntimeError):  # RuntimeError: no home directory
        return False
    digest = hashlib.sha256(f"{grammar}{lark.__version__}".encode()).hexdigest()[:16]
    return str(root / f"grammar-{digest}-py{sys.version_info[0]}{sys.version_info[1]}.lark")


@lru_cache(maxsize=1)
def _parser() -> Lark:
    grammar = GRAMMAR.read_text()
    return Lark(grammar, parser="lalr", lexer=_Tokens, maybe_placeholders=False, propagate_positions=True,
                cache=_cache_file(grammar))


def verb_list(lexicon: Lexicon) -> str:
    """A short list of verbs for messages ("pick" is left out when "pick up" is shown)."""
    shown = [v for action, n in (("pick", 8), ("place", 4), ("park", 1)) for v in lexicon.verbs(action)[:n]]
    return ", ".join(v for v in shown if not any(o.startswith(v + " ") for o in shown))


def parse(tokens: list[Token], lexicon: Lexicon, things: str) -> Request:
    """Parse tokens into a Request.

    Args:
        things: what the scene holds ("can x3, box x2"), for messages about unknown nouns.

    Raises:
        GroundingError: one line naming the unknown word or where the sentence stopped making sense.
    """
    toks = _row_per_name([t for t in tokens if t.cat not in DROPPED])
    if not toks:
        raise GroundingError("empty request: say what to do, e.g. 'pick up a can', 'put a cup on the table' or 'park'")
    first = toks[1] if toks[0].cat == "negation" and len(toks) > 1 else toks[0]
    if first.cat == "unknown":
        raise GroundingError(f"unknown word {first.text!r}{lexicon.hint(first.text, 'verb', only=True)}; supported verbs: {verb_list(lexicon)} (see docs/requests.md)")
    try:
        tree = _parser().parse(toks)
    except UnexpectedInput as exc:
        if first.cat not in ("verb", "manner"):  # neither a request nor a bare noun phrase ("the green cup")
            raise GroundingError(f"a request starts with a verb, not {first.text!r}; supported verbs: {verb_list(lexicon)} (see docs/requests.md)") from None
        raise _explain(exc, toks, lexicon, things) from None
    request = _Semantics(toks).transform(tree)
    return replace(request, clauses=tuple(_attach_positions(c) for c in request.clauses))


def _explain(exc: UnexpectedInput, toks: list[Token], lexicon: Lexicon, things: str) -> GroundingError:
    """One line for a request the grammar cannot read: the unknown word, a second verb, a missing object."""
    unknown = next((t for t in toks if t.cat == "unknown"), None)
    if unknown is not None:
        return GroundingError(f"unknown word {unknown.text!r}{lexicon.hint(unknown.text)}; objects here: {things}; verbs: {verb_list(lexicon)}")
    tok = getattr(exc, "token", None)
    i = tok.start_pos if tok is not None and isinstance(tok.start_pos, int) and tok.type != "$END" else len(toks)
    if i >= len(toks):
        return GroundingError(f"expected an object after {toks[-1].text!r}, e.g. '{toks[-1].text} the table'")
    t = toks[i]
    if t.cat == "verb":
        return GroundingError(f"not supported: a second verb {t.text!r}; ask for one action at a time")
    if t.cat == "number" and i > 0 and toks[i - 1].cat == "noun":
        return GroundingError(f"no '{toks[i - 1].text} {t.text}' in this scene{lexicon.ids_with(toks[i - 1].text)}")
    return GroundingError(f"unexpected {t.text!r} after '{' '.join(x.text for x in toks[1 if i > 1 else 0:i])}'")


@v_args(meta=True)
class _Semantics(Transformer):
    """The meaning of each grammar rule (method name = rule or alias name in grammar.lark)."""

    def __init__(self, toks: list[Token]):
        super().__init__()
        self.toks = toks

    def _tok(self, lt: LarkToken) -> Token:
        return self.toks[lt.start_pos]

    def _words(self, lo: int, hi: int) -> str:
        return " ".join(t.text for t in self.toks[lo:hi])

    # -- requests and clauses -------------------------------------------------------------

    def bare_request(self, meta, items):
        """A noun phrase alone means "get it" ("park in it" for a parking spot: see ground._frame)."""
        clause = self.clause(meta, [("verb", Token("", Entry("verb", "pick")), "")] + list(items))
        return Request((clause,))

    def start(self, meta, items):
        joiner = next((self._tok(i).text for i in items if isinstance(i, LarkToken)), "")
        return Request(tuple(i for i in items if isinstance(i, Clause)), joiner)

    def clause(self, meta, items):
        negated = isinstance(items[0], LarkToken) and items[0].type == "NEGATION"
        verb, manner = next(i for i in items if isinstance(i, tuple) and i and i[0] == "verb")[1:]
        objects, pps = (), []
        free_target = to_person = False
        conjunction = ""
        for it in items:
            if isinstance(it, list):  # objects
                objects, conjunction = tuple(x for x in it if isinstance(x, tuple)), next((x for x in it if isinstance(x, str)), "")
            elif isinstance(it, PrepPhrase):
                if it.prep.value == "target" and all(a.head in ("person", "robot") and not a.modifiers for a in it.alternatives):
                    to_person = True
                else:
                    pps.append(it)
            elif isinstance(it, tuple) and it and it[0] == "manner":
                manner = it[1]
            elif isinstance(it, tuple) and it and it[0] == "free":
                free_target = True
        return Clause(verb, objects, tuple(pps), manner, negated, to_person, free_target, conjunction)

    def verb(self, meta, items):
        toks = [self._tok(i) for i in items]
        verb = next((t for t in toks if t.cat == "verb"), None)
        manner = next((t.value for t in toks if t.cat == "manner"), "")
        if verb is None:  # "reverse into spot 4": the manner is the verb (and a constraint)
            verb = Token(toks[0].text, Entry("verb", "park"))
        return ("verb", verb, manner)

    def manner(self, meta, items):
        return ("manner", self._tok(items[0]).value)

    def free_target(self, meta, items):
        return ("free",)

    def pp(self, meta, items):
        return PrepPhrase(self._tok(items[0]), items[1])

    def objects(self, meta, items):
        return [i if isinstance(i, tuple) else self._tok(i).text for i in items]

    def choice(self, meta, items):
        return tuple(i for i in items if isinstance(i, NounPhrase))

    landmarks = choice

    # -- noun phrases -------------------------------------------------------------------------

    def np(self, meta, items):
        if items and isinstance(items[0], LarkToken) and items[0].type == "ONE":  # "one can", "one red box"
            items = [{"det": True, "determiner": "indefinite", "word": "one", "end": items[0].start_pos + 1, "quantity": None}] + items[1:]
        det = next((i for i in items if isinstance(i, dict) and "det" in i), {})
        head = next((i for i in items if isinstance(i, dict) and "head" in i), {})
        pre = [i for i in items if isinstance(i, Modifier) and i.order.startswith("@")]
        mods = tuple(replace(m, order="") if m.order.startswith("@") else m for m in items if isinstance(m, Modifier))
        mods += tuple(m for i in items if isinstance(i, tuple) and i and i[0] == "mods" for m in i[1])
        locs = tuple(loc for i in items if isinstance(i, tuple) and i and i[0] == "locations" for loc in i[1])
        excluded = tuple(x for i in items if isinstance(i, tuple) and i and i[0] == "excluded" for x in i[1])
        order = next((i for i in items if isinstance(i, tuple) and i and i[0] == "order"), None)
        if order is not None:
            if order[1] not in ORDER_SIDES | {"near"}:
                raise GroundingError(f"cannot count {order[2]!r}: say from the left, right, top or bottom")
            mods = tuple(replace(m, order=order[1]) if m.kind == "ordinal" else m for m in mods)
        if not mods and not head and not locs and det:
            raise GroundingError(f"expected an object after {det['word']!r}")
        lo = det.get("end", meta.start_pos)
        hi = head["end"] if head else max((int(m.order[1:]) + 1 for m in pre), default=lo)
        plural_head = head.get("plural", False)
        quantity = det.get("quantity") or (Quantity("all", None, det["word"]) if plural_head and det.get("determiner") == "definite"
                                           else Quantity("some", None, "") if plural_head and not det else Quantity())
        return NounPhrase(self._words(lo, hi), head.get("head", ""), head.get("value", ""), head.get("word", ""),
                          plural_head, det.get("determiner", ""), det.get("word", ""), quantity, mods, locs, excluded,
                          head.get("tails", ()), head.get("range"), False, det.get("different", False))

    landmark = np

    def _det(self, meta, determiner: str, quantity: Quantity | None, **extra) -> dict:
        return {"det": True, "determiner": determiner, "word": self._words(meta.start_pos, meta.end_pos),
                "end": meta.end_pos, "quantity": quantity, **extra}

    def det_simple(self, meta, items):
        return self._det(meta, self._tok(items[0]).value, None)

    def det_quant(self, meta, items):
        t = self._tok(items[0])
        kind, count = {"both": ("all", 2)}.get(t.value, (t.value, None))
        return self._det(meta, "definite", Quantity(kind, count, t.text))

    def det_count(self, meta, items):
        toks = [self._tok(i) for i in items]
        n = int(toks[-1].value)
        determiner = toks[0].value if len(toks) > 1 else "indefinite"
        return self._det(meta, determiner, Quantity() if n == 1 else Quantity("n", n, self._words(meta.start_pos, meta.end_pos)))

    def det_one(self, meta, items):
        return self._det(meta, "indefinite", None)

    def det_different(self, meta, items):
        return self._det(meta, "indefinite", None, different=True)

    # premodifiers: each a Modifier ("@i" remembers its token until the noun phrase is built)
    def _mod(self, kind, items, value=None):
        t = self._tok(items[0])
        return Modifier(kind, t.value if value is None else value, t.text, order=f"@{items[0].start_pos}")

    def colour(self, meta, items):
        return self._mod("colour", items)

    def size(self, meta, items):
        return self._mod("size", items)

    def position(self, meta, items):
        return self._mod("position", items)

    def superlative(self, meta, items):
        return self._mod("superlative", items)

    def ordinal(self, meta, items):
        return self._mod("ordinal", items)

    def state(self, meta, items):
        return self._mod("state", items)

    def attribute(self, meta, items):
        return self._mod("attribute", items, value=self._tok(items[0]).text)

    def negated_premod(self, meta, items):
        return replace(items[1], negated=not items[1].negated)

    # heads: dicts with the head kind and where it ends
    def _head(self, meta, kind, value=None, **extra):
        t = self.toks[meta.start_pos]
        return {"head": kind, "value": t.value if value is None else value, "word": t.text,
                "plural": bool(t.entry and t.entry.plural), "end": meta.end_pos, **extra}

    def noun(self, meta, items):
        return self._head(meta, "noun")

    def object_id(self, meta, items):
        return self._head(meta, "id")

    def wildcard(self, meta, items):
        return self._head(meta, "wildcard", "")

    def robot(self, meta, items):
        return self._head(meta, "robot")

    def person(self, meta, items):
        return self._head(meta, "person")

    def floor(self, meta, items):
        return self._head(meta, "floor")

    def pronoun(self, meta, items):
        return self._head(meta, "pronoun")

    def row(self, meta, items):
        return self._head(meta, "row", self._tok(items[1]).text if len(items) > 1 else "")

    def head(self, meta, items):
        return items[0]

    def pro_one(self, meta, items):
        return self._head(meta, "wildcard", "")

    def idref(self, meta, items):
        tails, rng = items[-1]
        noun = items[0] if isinstance(items[0], LarkToken) and items[0].type == "NOUN" else None
        head = self._head(meta, "idref", tails=tails, range=rng)
        return head if noun is not None else {**head, "value": "", "plural": False}

    def bare_idtail(self, meta, items):
        return self._head(meta, "idref", "", tails=(self._tok(items[0]).value,), range=None)

    def id_list(self, meta, items):
        return tuple(self._tok(i).value for i in items if i.type in ("NUMBER", "IDTAIL")), None

    def id_range(self, meta, items):
        lo, sep, hi = (self._tok(i) for i in (items[0], items[1], items[-1]))
        if sep.cat == "preposition" and sep.text != "to":
            raise GroundingError(f"unexpected {sep.text!r} in a range of ids; say e.g. 'spots 3 to 6'")
        if not (lo.value.isdigit() and hi.value.isdigit()):
            raise GroundingError(f"a range of ids needs numbers, not {lo.text!r} to {hi.text!r}")
        return (), (int(lo.value), int(hi.value))

    # postmodifiers
    def relation(self, meta, items):
        t = self._tok(items[0])
        return Modifier("relation", t.value, t.text, (items[1],))

    def between(self, meta, items):
        return Modifier("relation", "between", self._tok(items[0]).text, (items[1], items[3]))

    def distance(self, meta, items):
        t = self._tok(items[0])
        lm = items[-1] if isinstance(items[-1], NounPhrase) else None
        return Modifier("superlative", t.value, t.text, () if lm is None or lm.head in ("person", "robot") else (lm,))

    def relative(self, meta, items):
        negated = any(isinstance(i, LarkToken) and i.type == "NEGATION" for i in items)
        return _negate(items[-1], negated)

    def negated_post(self, meta, items):
        return _negate(items[-1], True)

    def layout(self, meta, items):
        return ("layout",)

    def from_side(self, meta, items):
        t = self._tok(items[-1])
        return ("order", t.value if t.cat == "position" else "near", self._words(meta.start_pos, meta.end_pos))

    def body_premods(self, meta, items):
        return ("mods", tuple(replace(i, order="") for i in items if isinstance(i, Modifier)))

    def body_pp(self, meta, items):
        return ("locations", (Location(self._tok(items[0]).text, (items[1],)),))

    def exclusion(self, meta, items):
        if isinstance(items[-1], NounPhrase):
            return ("excluded", (items[-1],))
        return ("excluded", (self.np(meta, items[1:]),))  # "not the red one"



def _negate(body, negated: bool):
    """A clause body as noun-phrase parts; "not" flips the filter in it."""
    if not negated:
        return body
    if isinstance(body, Modifier):
        return replace(body, negated=not body.negated)
    if body[0] == "mods":
        if len(body[1]) > 1:
            raise GroundingError("not supported: 'not' before several words; say e.g. 'not red'")
        return replace(body[1][0], negated=not body[1][0].negated)
    return ("locations", tuple(replace(loc, negated=True) for loc in body[1]))


def _attach_positions(c: Clause) -> Clause:
    """Noun-less position phrases ("on the left") narrow the phrase just before them."""
    groups: list[list[NounPhrase]] = [list(c.object)]
    preps: list[Token] = []
    for pp in c.pps:
        prev = groups[-1]
        if all(a.position_only for a in pp.alternatives) and prev:
            mods = tuple(m for a in pp.alternatives for m in a.modifiers)
            said = " or ".join(a.full() for a in pp.alternatives)
            groups[-1] = [replace(a, modifiers=a.modifiers + mods, text=f"{a.text} {pp.prep.text} {said}".strip()) for a in prev]
        else:
            groups.append(list(pp.alternatives))
            preps.append(pp.prep)
    objects = ((tuple(groups[0]),) + c.objects[1:]) if c.objects else ()
    return replace(c, objects=objects, pps=tuple(PrepPhrase(p, tuple(g)) for p, g in zip(preps, groups[1:])))
