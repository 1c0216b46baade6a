"""Generated parking lots: N free spots, k of them reachable (issue #33).

The lot is a stack of bays, each an east-west aisle between two rows of spots,
joined by a cross aisle on the west side where the car starts. Rows back onto
kerbs (or the outer walls); low rails separate a reachable spot from a blocked
neighbour. Every free spot's parked pose is collision-free; the unreachable
ones are blocked in one of three ways:

* ``barrier`` — a rail across the spot's mouth (one rail spans a run of them);
* ``gated`` — the whole bay is closed off from the cross aisle by a wall;
* ``narrow`` — two posts at the mouth leave 1.6 m, less than the car's 1.8 m.

Some spots are occupied (the Drake world parks a car in them). The layout is
seeded: the same (free, reachable, seed) always gives the same scene.

Two modes. By default the lot grows with N (about 1/8 of its spots occupied), so a larger N
is also a larger lot to explore. With ``slots`` > 0 the layout is fixed (``slots`` spots,
the same bays, gates and reachable spots for every N) and N only says how many of the
blocked spots are free rather than holding a parked car: the free ones of a smaller N are
among those of a larger one, so only the number of interpretations changes. A run of
parked cars there is one box (Drake's geometry registration is quadratic in the boxes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lazyground.settings import Algorithm, GoalExtension, Kinematics, Strategy

SPOT_W, SPOT_D = 2.6, 5.5  # a spot's width and depth (m)
AISLE = 7.0  # aisle width: a 3.86 m turning radius car turns into a spot from it
CROSS = 8.0  # the west cross aisle's width
BAY = 2 * SPOT_D + AISLE
KERB = 0.2
RAIL = 0.1
PARKED_LEN, PARKED_GAP = 4.5, 0.4  # a parked car's length, and its gap to the spot's side lines
CHUNK = 8  # a fixed layout's blocked spots turn free this many neighbours at a time
NARROW_GAP = 1.6  # the narrow spots' mouth: less than the car's width (1.8 m)
REACHABLE, BARRIER, NARROW, GATED, OCCUPIED = "reachable", "barrier", "narrow", "gated", "occupied"


@dataclass(frozen=True)
class LotSpec:
    """What to generate; ``occupied`` is the fraction of spots with a parked car (beside the N free ones)."""

    free: int
    reachable: int = 2
    seed: int = 0
    occupied: float = 0.125
    gated: float = 0.3  # the fraction of bays (not the first open one) closed off
    narrow: float = 0.1  # the fraction of blocked spots in open bays with a narrow mouth instead of a barrier
    slots: int = 0  # > 0: a fixed layout of this many spots, the blocked ones not free holding parked cars

    def __post_init__(self):
        if not 1 <= self.free <= 4096:
            raise ValueError(f"free spots must be in [1, 4096], got {self.free}")
        if self.slots and not self.free <= self.slots <= 4096:
            raise ValueError(f"a fixed layout's spots must be in [free={self.free}, 4096], got {self.slots}")
        if not 0 <= self.reachable <= self.free:
            raise ValueError(f"reachable spots must be in [0, free={self.free}], got {self.reachable}")


def _box(id_, x, y, sx, sy, h, color=None) -> dict:
    out = {"id": id_, "geometry": {"box": [round(sx, 4), round(sy, 4), h]},
           "pose": {"xyz": [round(x, 4), round(y, 4), h / 2]}}
    if color:
        out["color"] = color
    return out


def _layout(slots: int) -> tuple[int, int]:
    """(bays, columns) for at least ``slots`` spots, the lot about square."""
    bays = max(1, math.ceil(math.sqrt(slots * SPOT_W / (2 * BAY))))
    return bays, max(2, math.ceil(slots / (2 * bays)))


def _gated_bays(spec: LotSpec, rng: np.random.Generator, bays: int, cols: int) -> np.ndarray:
    """Which bays a wall closes off (never so many that the reachable spots have no open bay)."""
    gated = np.zeros(bays, bool)
    open_needed = math.ceil(spec.reachable / (2 * cols)) if spec.reachable else 0
    order = rng.permutation(bays)
    n_gated = min(int(round(spec.gated * bays)), bays - max(1, open_needed))
    gated[order[:n_gated]] = True
    return gated


def _classes(spec: LotSpec, rng: np.random.Generator, bays: int, cols: int) -> tuple[np.ndarray, np.ndarray]:
    """A class per slot, shape (bays, 2 rows, cols): exactly ``free`` free spots, ``reachable`` of them
    reachable; and which bays are gated."""
    slots = bays * 2 * cols
    n_occ = slots - spec.free
    gated = _gated_bays(spec, rng, bays, cols)
    cls = np.full((bays, 2, cols), BARRIER, dtype=object)
    cls[gated] = GATED
    # occupied spots and reachable spots both in open bays; the rest of the open bays blocked at the mouth
    open_slots = [(b, r, c) for b in range(bays) if not gated[b] for r in range(2) for c in range(cols)]
    picks = rng.permutation(len(open_slots))
    n_occ_open = min(n_occ, len(open_slots) - spec.reachable)
    for i in picks[:spec.reachable]:
        cls[open_slots[i]] = REACHABLE
    for i in picks[spec.reachable:spec.reachable + n_occ_open]:
        cls[open_slots[i]] = OCCUPIED
    gated_slots = [(b, r, c) for b in range(bays) if gated[b] for r in range(2) for c in range(cols)]
    for i in rng.permutation(len(gated_slots))[:n_occ - n_occ_open]:
        cls[gated_slots[i]] = OCCUPIED
    for i in picks[spec.reachable + n_occ_open:]:
        if rng.random() < spec.narrow:
            cls[open_slots[i]] = NARROW
    return cls, gated


def _fixed_classes(spec: LotSpec, rng: np.random.Generator, bays: int, cols: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_classes` of a fixed layout: the gates, the reachable spots and the order in which blocked
    spots turn from occupied to free are drawn without looking at ``free`` (nested free sets). The
    reachable spots lie in the start's bay (the time to drive to them is not what N should change).

    Blocked spots turn free a block of ``CHUNK`` neighbours in a row at a time (blocks in random
    order, narrow or barrier per block): runs of free and of parked spots stay long, so the world
    has few boxes."""
    gated = _gated_bays(spec, rng, bays, cols)
    gated[0] = False  # the start's bay: the reachable spots are there, at most ~100 m away whatever N is
    near = [(0, r, c) for r in range(2) for c in range(cols)]
    if spec.reachable > len(near):
        raise ValueError(f"a fixed layout of {spec.slots} spots has room for {len(near)} reachable ones, not {spec.reachable}")
    reach = {near[i] for i in rng.permutation(len(near))[:spec.reachable]}
    blocks = [[(b, r, c) for c in range(c0, min(c0 + CHUNK, cols)) if (b, r, c) not in reach]
              for b in range(bays) for r in range(2) for c0 in range(0, cols, CHUNK)]
    order, narrow = rng.permutation(len(blocks)), rng.random(len(blocks)) < spec.narrow
    cls = np.full((bays, 2, cols), OCCUPIED, dtype=object)
    for slot in reach:
        cls[slot] = REACHABLE
    todo = spec.free - spec.reachable
    for i in order:
        for slot in blocks[i][:todo]:
            cls[slot] = GATED if gated[slot[0]] else NARROW if narrow[i] else BARRIER
        todo -= min(todo, len(blocks[i]))
    return cls, gated


def _runs(row: np.ndarray, kind: str) -> list[tuple[int, int]]:
    """(first, last) column of each run of ``kind`` in a row."""
    out, c = [], 0
    while c < len(row):
        if row[c] != kind:
            c += 1
            continue
        end = c
        while end + 1 < len(row) and row[end + 1] == kind:
            end += 1
        out.append((c, end))
        c = end + 1
    return out


def generate_lot(spec: LotSpec) -> dict:
    """The scene (a dict for the scene YAML) of a lot with ``spec.free`` free spots, ``spec.reachable`` reachable."""
    rng = np.random.default_rng(spec.seed)
    slots = spec.slots or spec.free + int(round(spec.occupied * spec.free))
    bays, cols = _layout(slots)
    cls, gated = (_fixed_classes if spec.slots else _classes)(spec, rng, bays, cols)
    W, H = CROSS + cols * SPOT_W, bays * BAY
    obstacles = [
        _box("wall_south", W / 2, -0.15, W + 0.6, 0.3, 2.0), _box("wall_north", W / 2, H + 0.15, W + 0.6, 0.3, 2.0),
        _box("wall_west", -0.15, H / 2, 0.3, H, 2.0), _box("wall_east", W + 0.15, H / 2, 0.3, H, 2.0),
    ]
    objects, kinds = [], {}
    for b in range(bays):
        y0 = b * BAY
        if b > 0:  # the kerb between this bay's south row and the bay below's north row
            obstacles.append(_box(f"kerb_{b}", CROSS + cols * SPOT_W / 2, y0, cols * SPOT_W, KERB, 0.3, "grey"))
        if gated[b] and (spec.slots or (cls[b] == GATED).any()):
            obstacles.append(_box(f"gate_{b}", CROSS - 0.15, y0 + BAY / 2, 0.3, BAY - KERB, 2.0, "red"))
        for r in range(2):  # row 0 faces north from the bay's south side, row 1 faces south
            yc = y0 + SPOT_D / 2 if r == 0 else y0 + BAY - SPOT_D / 2
            y_mouth = y0 + SPOT_D + (RAIL / 2 + 0.05) if r == 0 else y0 + BAY - SPOT_D - (RAIL / 2 + 0.05)
            yaw = -math.pi / 2 if r == 0 else math.pi / 2
            row = cls[b, r]
            for c in range(cols):
                sid = f"spot_{b}_{'sn'[r]}{c}"
                x = CROSS + (c + 0.5) * SPOT_W
                if row[c] == OCCUPIED and spec.slots:
                    continue  # a fixed layout's parked cars: one box per run, below
                objects.append({"id": sid, "type": "parking_spot", "geometry": {"box": [SPOT_W, SPOT_D, 0.05]},
                                "pose": {"xyz": [round(x, 4), round(yc, 4), 0.0], "rpy": [0, 0, round(yaw, 6)]},
                                "occupied": bool(row[c] == OCCUPIED)})
                if row[c] != OCCUPIED:
                    kinds[sid] = row[c]
                if row[c] == NARROW:
                    post = (SPOT_W - NARROW_GAP) / 2
                    for k, side in enumerate((-1, 1)):
                        obstacles.append(_box(f"post_{sid}_{k}", x + side * (SPOT_W - post) / 2, y_mouth, post, 0.15, 1.0, "red"))
                # a rail on the side line between an enterable spot (or the cross aisle) and a blocked free one
                left = row[c - 1] if c > 0 else REACHABLE
                if (left in (REACHABLE,)) != (row[c] in (REACHABLE,)) and OCCUPIED not in (left, row[c]) \
                        and GATED not in (left, row[c]):
                    xr = CROSS + c * SPOT_W
                    obstacles.append(_box(f"rail_{sid}", xr, yc, RAIL, SPOT_D - 0.2, 0.3, "grey"))
            # one mouth barrier across each run of barrier spots
            for c, end in _runs(row, BARRIER):
                x0, x1 = CROSS + c * SPOT_W, CROSS + (end + 1) * SPOT_W
                obstacles.append(_box(f"barrier_{b}_{'sn'[r]}{c}", (x0 + x1) / 2, y_mouth, x1 - x0, 0.15, 0.5, "red"))
            for c, end in _runs(row, OCCUPIED) if spec.slots else ():  # a run of parked cars (4.5 x 1.8 m each)
                x0, x1 = CROSS + c * SPOT_W + PARKED_GAP, CROSS + (end + 1) * SPOT_W - PARKED_GAP
                obstacles.append(_box(f"parked_{b}_{'sn'[r]}{c}", (x0 + x1) / 2, yc, x1 - x0, PARKED_LEN, 1.5, "brown"))
    if spec.slots:  # the goal source takes the spots in file order: not the start's bay (the reachable spots) first
        objects = [objects[i] for i in np.random.default_rng(spec.seed).permutation(len(objects))]
    reachable = sorted(k for k, v in kinds.items() if v == REACHABLE)
    start_y = min(H / 2, BAY / 2)
    counts = {v: sum(1 for x in kinds.values() if x == v) for v in (REACHABLE, BARRIER, NARROW, GATED)}
    fixed = f"_of{spec.slots}" if spec.slots else ""
    return {
        "name": f"lot_{spec.free}_{spec.reachable}_s{spec.seed}{fixed}",
        "description": (f"Generated lot (issue #33): {spec.free} free spots{f' of {spec.slots} (fixed layout)' if fixed else ''}, {counts[REACHABLE]} reachable; blocked: "
                        f"{counts[BARRIER]} barrier, {counts[GATED]} gated bay, {counts[NARROW]} narrow mouth; seed {spec.seed}."),
        "robot": {"model": "car", "start": {"car_x": CROSS / 2, "car_y": round(start_y, 3), "car_qz": round(math.pi / 2, 6)},
                  "limits": {"car_x": [0.0, round(W, 3)], "car_y": [0.0, round(H, 3)]}, "weights": {"car_qz": 2.0}},
        "obstacles": obstacles,
        "objects": objects,
        "planner": {"strategy": Strategy.COVER_CONNECT.value, "algorithm": Algorithm.BIDIRECTIONAL.value, "goal_bias": 0.05, "step_size": 2.0, "edge_resolution": 0.1,
                    "time_limit": 20.0, "seed": 0, "goal_extension": GoalExtension.EXTEND.value,
                    "kinematics": Kinematics.REEDS_SHEPP.value},
        "expect": [{"request": "park", "success_rate": 0.9, "seeds": 3, "time_limit": 60.0, "reachable": reachable}],
    }


def spot_kinds(scene: dict) -> dict[str, str]:
    """Each free spot's kind, read back from a generated scene (for tests and reports)."""
    obstacles = {o["id"] for o in scene["obstacles"]}
    out = {}
    for o in scene["objects"]:
        if o["occupied"]:
            continue
        sid = o["id"]
        b = sid.split("_")[1]
        if f"gate_{b}" in obstacles:
            out[sid] = GATED
        elif f"post_{sid}_0" in obstacles:
            out[sid] = NARROW
        elif sid in scene["expect"][0]["reachable"]:
            out[sid] = REACHABLE
        else:
            out[sid] = BARRIER
    return out
