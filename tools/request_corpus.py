"""A generated request corpus as the grounding's test oracle (#29), in the spirit of RoboCup@Home's GPSR
command generator: a grammar of request templates over a scene's contents, each request paired with
its meaning (``tools.request_oracle.Desc``), whose expected interpretations the independent oracle
computes from the scene's geometry and attributes.

Run: ``python3 -m tools.request_corpus [--per-scene 200] [--generated 20] [--seed 0] [--show-wrong 20]``.
It prints grounded right / refused / wrong over the bundled scenes (yaml_scenes/) and generated ones.
A request whose meaning names nothing is expected to be refused (counted apart).
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from tools.request_oracle import PICKABLE, SPOT, SUPPORTS, Desc, expected, support  # noqa: E402

NOUNS = {"can": ["can", "tin", "soda can"], "cup": ["cup", "mug"], "box": ["box", "cube", "carton"], "bottle": ["bottle"],
         "table": ["table", "desk"], "shelf": ["shelf", "rack"], "counter": ["counter", "worktop"], "cabinet": ["cabinet", "cupboard"],
         SPOT: ["spot", "space", "bay", "slot", "parking spot"]}
PLURALS = {"box": "boxes", "shelf": "shelves", "parking spot": "parking spots"}
COLOURS = ["red", "green", "blue", "yellow", "white", "black", "brown", "orange"]
ORDINALS = ["first", "second", "third", "fourth"]
PICK_VERBS = ["pick up", "grab", "get me", "fetch", "bring me", "take", "I need", "I'd like", "could I have", "can you get me",
              "hand me", "please pick up", "I want", "would you grab"]
PREFIX = ["", "", "", "please ", "hey robot, ", "could you ", "would you kindly "]
SUFFIX = ["", "", "", " please", ", thanks", "?", " for me"]
BUNDLED = sorted((ROOT / "yaml_scenes").glob("*.yaml"))


@dataclass(frozen=True)
class Item:
    """One corpus request: its text, action and meaning (object choice, target choice)."""

    scene: str
    text: str
    action: str
    objects: tuple[Desc, ...] = ()
    targets: tuple[Desc, ...] = ()


def expected_ids(scene, item: Item) -> set[str]:
    """The interpretation ids the oracle expects (empty: the request should be refused)."""
    if item.action == "park":
        return {f"park:{i}" for d in item.targets for i in expected(scene, d, "park")}
    objs = {i for d in item.objects for i in expected(scene, d, "pick")}
    if item.action == "pick":
        return {f"pick:{i}" for i in objs}
    targets = {i for d in item.targets for i in expected(scene, d, "support")}
    return {f"place:{o}:{t}" for o in objs for t in targets if o != t}


# -- the template grammar --------------------------------------------------------------------------

def _pick(rng, seq):
    return seq[int(rng.integers(len(seq)))]


def _plural(word: str) -> str:
    return PLURALS.get(word, word + ("es" if word.endswith(("x", "s")) else "s"))


def _landmark(rng, scene, o, rel: str):
    """A landmark near ``o`` for a relation, described by colour and noun (or None)."""
    others = [x for x in scene.objects if x.id != o.id and x.type in PICKABLE | SUPPORTS]
    if not others:
        return None
    lm = _pick(rng, others)
    colour = (lm.color or "").lower() if lm.color and rng.random() < 0.6 and lm.color.lower() in COLOURS else None
    text = f"the {colour + ' ' if colour else ''}{_pick(rng, NOUNS[lm.type])}"
    return Desc(type=lm.type, colour=colour), text


def _object_phrase(rng, scene, o):
    """(text, Desc) for a phrase built from 1-2 features that hold for object ``o`` (or deliberately not)."""
    noun = _pick(rng, NOUNS[o.type])
    d = Desc(type=o.type)
    colour = (o.color or "").lower()
    det = _pick(rng, ["the", "a", "any", "the"])
    pre, post = "", ""
    features = list(rng.permutation(["colour", "support", "not_colour", "except", "relation", "id", "closest", "ordinal", "side"]))
    # a plain support phrase ("on the table") goes last: a postmodifier after it would describe the table
    chosen = sorted(features[: int(rng.integers(1, 3))], key=lambda f: f == "support")
    for f in chosen:
        if f == "colour" and colour in COLOURS and not pre:
            d = replace(d, colour=colour)
            form = int(rng.integers(4))
            if form == 0:
                pre = colour + " "
            elif form == 1:
                pre = f"{colour} colored "
            else:
                post += f" {'that' if form == 2 else 'which'} is {colour}"
        elif f == "support":
            s = support(scene, o)
            if s in (None, "floor"):
                continue
            so = next(x for x in scene.objects if x.id == s)
            by_id = rng.random() < 0.25
            d = replace(d, on=Desc(id=so.id) if by_id else Desc(type=so.type))
            where = so.id if by_id else f"the {_pick(rng, NOUNS[so.type])}"
            post += _pick(rng, [f" on {where}", f" which is on {where}", f" sitting on {where}", f" from {where}", f" that is on {where}"])
        elif f == "not_colour" and d.colour is None:
            c = _pick(rng, COLOURS)
            d = replace(d, not_colour=c)
            post += _pick(rng, [f" that is not {c}", f" that isn't {c}", f" which is not {c}"])
        elif f == "except" and d.except_colour is None:
            c = _pick(rng, COLOURS)
            d = replace(d, except_colour=c)
            det = _pick(rng, ["any", "a"])
            post += _pick(rng, [f" except the {c} one", f" but not the {c} one", f" other than the {c} ones", f" except for the {c} ones"])
        elif f == "relation" and d.rel is None:
            rel = _pick(rng, ["next_to", "next_to", "left_of", "right_of"])
            lm = _landmark(rng, scene, o, rel)
            if lm is None:
                continue
            d = replace(d, rel=(rel, lm[0]))
            word = {"next_to": _pick(rng, ["next to", "beside", "near", "by"]), "left_of": _pick(rng, ["left of", "to the left of"]),
                    "right_of": _pick(rng, ["right of", "to the right of"])}[rel]
            post += f" {word} {lm[1]}"
        elif f == "id" and re.search(r"[0-9]+$", o.id) and len(chosen) == 1:
            n = int(re.search(r"([0-9]+)$", o.id).group(1))
            d = replace(d, id_num=n)
            return _pick(rng, [f"{noun} {n}", f"{noun} number {n}", f"{noun} #{n}", f"{noun} no. {n}"]), d
        elif f == "closest" and not d.closest and d.ordinal is None:
            d = replace(d, closest=True)
            det = "the"
            form = int(rng.integers(4))
            if form == 0:
                pre = "closest " + pre
            elif form == 1:
                pre = "nearest " + pre
            else:
                post = _pick(rng, [" closest to you", " nearest to the robot", " closest to me", " nearest you"]) + post
        elif f in ("ordinal", "side") and d.ordinal is None and not d.closest and d.except_colour is None:
            n = int(rng.integers(1, 4))
            side = _pick(rng, ["left", "right"])
            d = replace(d, ordinal=(n, side))
            det = "the"
            pre = f"{ORDINALS[n - 1]} " + pre
            post = f" from the {side}" + post
    if det in ("a", "any") and rng.random() < 0.3 and not pre and not post:
        return f"one of the {_plural(noun)}", d
    return f"{det} {pre}{noun}{post}", d


def _pick_item(rng, scene, name):
    objs = [o for o in scene.objects if o.type in PICKABLE]
    o = _pick(rng, objs)
    text, d = _object_phrase(rng, scene, o)
    if rng.random() < 0.08:  # a noun phrase alone: "the red cup, please"
        return Item(name, f"{text}{_pick(rng, [', please', ' please', '', '?'])}", "pick", (d,))
    verb = _pick(rng, PICK_VERBS)
    return Item(name, f"{_pick(rng, PREFIX)}{verb} {text}{_pick(rng, SUFFIX)}", "pick", (d,))


def _place_item(rng, scene, name):
    objs = [o for o in scene.objects if o.type in PICKABLE]
    sups = [o for o in scene.objects if o.type in SUPPORTS]
    if not sups:
        return _pick_item(rng, scene, name)
    o, s = _pick(rng, objs), _pick(rng, sups)
    text, d = _object_phrase(rng, scene, o)
    by_id = rng.random() < 0.3
    target = Desc(id=s.id) if by_id else Desc(type=s.type)
    where = s.id if by_id else f"the {_pick(rng, NOUNS[s.type])}"
    verb = _pick(rng, ["put", "place", "set", "move", "take"])
    prep = "to" if verb == "take" else _pick(rng, ["on", "onto"])
    return Item(name, f"{_pick(rng, PREFIX)}{verb} {text} {prep} {where}{_pick(rng, SUFFIX)}", "place", (d,), (target,))


def _tail(spot_id: str) -> str:
    parts = spot_id.split("_")
    return parts[-1] if len(parts) > 1 else spot_id


def _park_item(rng, scene, name):
    spots = [o for o in scene.objects if o.type == SPOT]
    s = _pick(rng, spots)
    noun = _pick(rng, NOUNS[SPOT])
    any_spot = Desc(type=SPOT)
    form = int(rng.integers(9))
    if form == 0:
        text, t = _pick(rng, ["park", "go park", "park anywhere", "park somewhere", "park the car anywhere", "find a spot and park",
                              "find a free spot and park", "leave the car in any free spot", f"park in a free {noun}",
                              f"pull into any empty {noun}", "park wherever", f"find me an empty {noun}"]), (any_spot,)
    elif form in (1, 2):
        tail = _tail(s.id)
        t = (Desc(type=SPOT, id_tail=tail),)
        text = _pick(rng, [f"park in {noun} {tail}", f"park at {tail}", f"reverse into {noun} {tail}", f"leave the car in {noun} {tail}",
                           f"back into {noun} {tail}", f"park the car in {noun} {tail}"])
    elif form == 3:
        other = _pick(rng, spots)
        t = (Desc(type=SPOT, id_tail=_tail(s.id)), Desc(type=SPOT, id_tail=_tail(other.id)))
        text = f"park in {noun} {_tail(s.id)} or {_tail(other.id)}"
    elif form == 4:
        t = (replace(any_spot, closest=True),)
        text = _pick(rng, [f"park in the {noun} closest to you", f"park in the closest free {noun}", f"park in the nearest {noun}"])
    elif form == 5:
        t = (Desc(type=SPOT, rel=("next_to", Desc(type=SPOT, id_tail=_tail(s.id)))),)
        text = _pick(rng, [f"park next to {noun} {_tail(s.id)}", f"park in a {noun} beside {noun} {_tail(s.id)}"])
    elif form == 6:
        other = _pick(rng, spots)
        t = (Desc(type=SPOT, between=(Desc(type=SPOT, id_tail=_tail(s.id)), Desc(type=SPOT, id_tail=_tail(other.id)))),)
        text = f"park between {noun} {_tail(s.id)} and {noun} {_tail(other.id)}"
    elif form == 7:
        t = (Desc(type=SPOT, id_tail=_tail(s.id)),)
        text = f"park in {s.id}"
    else:
        c = _pick(rng, ["left", "right"])
        t = (Desc(type=SPOT, rel=(f"{c}_of", Desc(type=SPOT, id_tail=_tail(s.id)))),)
        text = f"park in a {noun} to the {c} of {noun} {_tail(s.id)}"
    return Item(name, f"{_pick(rng, PREFIX)}{text}{_pick(rng, SUFFIX)}", "park", (), t)


def generate(scene, name: str, n: int, rng: np.random.Generator) -> list[Item]:
    """``n`` requests over one scene."""
    if any(o.type == SPOT for o in scene.objects):
        return [_park_item(rng, scene, name) for _ in range(n)]
    return [_place_item(rng, scene, name) if rng.random() < 0.25 else _pick_item(rng, scene, name) for _ in range(n)]


# -- generated scenes ------------------------------------------------------------------------------

def tabletop_scene(rng: np.random.Generator, name: str) -> str:
    """A Fetch before one or two tables with cans, cups, boxes and bottles; the base pose is random."""
    x0, y0, yaw = rng.uniform(-1, 1), rng.uniform(-1, 1), float(rng.choice([0.0, math.pi / 2, math.pi, -math.pi / 2, rng.uniform(-3, 3)]))
    c, s = math.cos(yaw), math.sin(yaw)
    world = lambda u, v: (round(x0 + c * u - s * v, 4), round(y0 + s * u + c * v, 4))
    lines = [f"name: {name}", "robot:", "  model: fetch", f"  base: {{xyz: [{x0:.4f}, {y0:.4f}, 0], rpy: [0, 0, {yaw:.6f}]}}",
             "  end_effector: gripper_link", "  start: {torso_lift_joint: 0.05}", "objects:"]
    tables = [(0.9, 0.0)] + ([(0.3, 1.1)] if rng.random() < 0.6 else [])
    count = {}
    for k, (u, v) in enumerate(tables):
        x, y = world(u, v)
        kind = "table" if k == 0 or rng.random() < 0.5 else "counter"
        lines.append(f"- {{id: {kind}_{k + 1}, type: {kind}, geometry: {{box: [0.7, 0.9, 0.04]}}, pose: {{xyz: [{x}, {y}, 0.70], rpy: [0, 0, {yaw:.6f}]}}}}")
        slots = [(u + du, v + dv) for du in (-0.2, 0.0, 0.2) for dv in (-0.3, -0.1, 0.1, 0.3)]
        for j in rng.permutation(len(slots))[: int(rng.integers(3, 8))]:
            su, sv = slots[j]
            t = str(rng.choice(["can", "cup", "box", "bottle", "can", "cup"]))
            count[t] = count.get(t, 0) + 1
            colour = str(rng.choice(COLOURS[:6]))
            ox, oy = world(su + rng.uniform(-0.03, 0.03), sv + rng.uniform(-0.03, 0.03))
            if t == "box":
                geo, h = "{box: [0.06, 0.06, 0.08]}", 0.08
            elif t == "bottle":
                geo, h = "{cylinder: {radius: 0.03, length: 0.2}}", 0.2
            else:
                geo, h = "{cylinder: {radius: 0.035, length: 0.11}}", 0.11
            lines.append(f"- {{id: {t}_{count[t]}, type: {t}, color: {colour}, geometry: {geo}, pose: {{xyz: [{ox}, {oy}, {0.72 + h / 2:.4f}]}}}}")
    return "\n".join(lines) + "\n"


def parking_scene(rng: np.random.Generator, name: str) -> str:
    """A lot with one or two rows of spots (random occupancy) and the car at a random pose in the aisle."""
    n = int(rng.integers(5, 11))
    rows = [("a", 2.75, -1.570796)] + ([("b", 17.25, 1.570796)] if rng.random() < 0.7 else [])
    qz = float(rng.choice([0.0, math.pi, rng.uniform(-3, 3)]))
    lines = [f"name: {name}", "robot:", "  model: car", f"  start: {{car_x: {rng.uniform(2, 8):.3f}, car_y: {rng.uniform(8, 12):.3f}, car_qz: {qz:.4f}}}",
             "  limits: {car_x: [0, 40], car_y: [0, 20]}", "objects:"]
    for row, y, yaw in rows:
        for k in range(n):
            occupied = "true" if rng.random() < 0.5 else "false"
            lines.append(f"- {{id: spot_{row}{k}, type: parking_spot, geometry: {{box: [5.5, 2.6, 0.05]}}, "
                         f"pose: {{xyz: [{2 + 2.6 * k:.2f}, {y}, 0], rpy: [0, 0, {yaw}]}}, occupied: {occupied}}}")
    return "\n".join(lines) + "\n"


def scenes(generated: int, seed: int):
    """(name, Scene) for the bundled scenes and ``generated`` generated ones (half tabletops, half lots)."""
    from lazyground.scene import load_scene, parse_scene

    out = [(p.stem, load_scene(p)) for p in BUNDLED]
    rng = np.random.default_rng(np.random.SeedSequence(seed).spawn(1)[0])
    for k in range(generated):
        name = f"gen_{'table' if k % 2 == 0 else 'lot'}_{k}"
        text = tabletop_scene(rng, name) if k % 2 == 0 else parking_scene(rng, name)
        out.append((name, parse_scene(text, name)))
    return out


# -- running the grounder against the oracle ------------------------------------------------------

UNFIT = re.compile(r"(\S+) cannot be grasped")


@dataclass(frozen=True)
class Outcome:
    item: Item
    expected: frozenset
    got: frozenset | None  # None: refused
    message: str
    ms: float

    @property
    def verdict(self) -> str:
        if self.got is None:
            return "refused" if self.expected else "refused_right"
        return "right" if self.got == self.expected else "wrong"


def run_item(scene, item: Item, ground, error) -> Outcome:
    """Ground one request; objects the gripper cannot hold (named in the notes) are taken out of both sides."""
    want = expected_ids(scene, item)
    t0 = time.process_time()  # CPU time: on a shared machine the wall clock measures the neighbours too
    try:
        g = ground(item.text, scene)
    except error as exc:
        ms = (time.process_time() - t0) * 1e3
        unfit = set(UNFIT.findall(str(exc)))
        if unfit and unfit <= {i.split(":")[1] for i in want}:  # every match is too big for the gripper
            return Outcome(item, frozenset(), frozenset(), str(exc), ms)
        return Outcome(item, frozenset(want), None, str(exc), ms)
    ms = (time.process_time() - t0) * 1e3
    unfit = {u for n in g.notes for u in UNFIT.findall(n)}
    want = {i for i in want if i.split(":")[1] not in unfit}
    return Outcome(item, frozenset(want), frozenset(i.id for i in g.interpretations), "; ".join(g.notes), ms)


def run(per_scene: int = 200, generated: int = 20, seed: int = 0, sample: int | None = None) -> list[Outcome]:
    """Generate the corpus and ground every request (or a seeded ``sample`` of it)."""
    import grounding

    rng = np.random.default_rng(seed)
    out = []
    for name, sc in scenes(generated, seed):
        for item in generate(sc, name, per_scene, rng):
            out.append((sc, item))
    if sample is not None:
        idx = np.random.default_rng(seed + 1).choice(len(out), size=min(sample, len(out)), replace=False)
        out = [out[i] for i in sorted(idx)]
    return [run_item(sc, item, grounding.ground, grounding.GroundingError) for sc, item in out]


def summary(outcomes: list[Outcome]) -> dict:
    counts = {k: sum(o.verdict == k for o in outcomes) for k in ("right", "refused", "wrong", "refused_right")}
    meant = counts["right"] + counts["refused"] + counts["wrong"]
    ms = sorted(o.ms for o in outcomes)
    bundled = sorted(o.ms for o in outcomes if not o.item.scene.startswith("gen_"))
    return {**counts, "total": len(outcomes), "grounded_share": counts["right"] / meant if meant else 1.0,
            "median_ms": ms[len(ms) // 2] if ms else 0.0, "p99_ms": ms[int(0.99 * (len(ms) - 1))] if ms else 0.0,
            "bundled_median_ms": bundled[len(bundled) // 2] if bundled else 0.0,
            "bundled_p99_ms": bundled[int(0.99 * (len(bundled) - 1))] if bundled else 0.0,
            "bundled_max_ms": bundled[-1] if bundled else 0.0}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--per-scene", type=int, default=200)
    ap.add_argument("--generated", type=int, default=20)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--show", type=int, default=10, help="print this many wrong and refused requests")
    args = ap.parse_args(argv)
    outcomes = run(args.per_scene, args.generated, args.seed)
    s = summary(outcomes)
    print(f"requests {s['total']} over {len(BUNDLED)} bundled + {args.generated} generated scenes (seed {args.seed})")
    print(f"grounded right {s['right']}, refused {s['refused']}, wrong {s['wrong']}; "
          f"grounded {100 * s['grounded_share']:.1f}% of those that name something; "
          f"{s['refused_right']} naming nothing were refused as they should be")
    print(f"grounding CPU time per request: median {s['median_ms']:.2f} ms, p99 {s['p99_ms']:.2f} ms; "
          f"bundled scenes: median {s['bundled_median_ms']:.2f} ms, p99 {s['bundled_p99_ms']:.2f} ms, max {s['bundled_max_ms']:.2f} ms")
    for kind in ("wrong", "refused"):
        for o in [o for o in outcomes if o.verdict == kind][: args.show]:
            print(f"{kind}: [{o.item.scene}] {o.item.text!r}: expected {sorted(o.expected)}, got {sorted(o.got) if o.got is not None else None} {o.message[:160]}")
    return 1 if s["wrong"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
