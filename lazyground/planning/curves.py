"""Shortest car paths: Reeds-Shepp (forwards and reverse) and Dubins (forwards only).

Written for this project from the formulas of Reeds and Shepp, "Optimal paths for
a car that goes both forwards and backwards", Pacific J. Math. 145(2), 1990
(eqs. 8.1-8.11; the typos in 8.3/8.4 and 8.11 corrected as in OMPL), and of
Shkel and Lumelsky, "Classification of the Dubins set", RAS 34, 2001. Lengths
are in units of the turning radius: a path is a tuple of segments
``(kind, signed length)`` with kind "L", "R" or "S" and a negative length
meaning reverse gear. A handful of base words are solved in closed form; the
other 40 Reeds-Shepp words are their images under three symmetries (time flip:
drive the word backwards; reflection: swap left and right; backwards: the word
read end to start), applied generically below rather than spelled out per word.

Pure Python scalars (``math``): one query evaluates ~50 closed forms, and numpy's
per-call overhead on 3-element arrays would cost more than the arithmetic.
"""

from __future__ import annotations

import math

PI = math.pi
TWO_PI = 2.0 * math.pi
HALF_PI = 0.5 * math.pi
# A length this close to 0 still counts as having its sign. OMPL's 10 ulp of a unit is too tight for poses tens of
# radii from the origin: a 0.1 m straight piece of a dense path, re-solved, came out a 0.23 m L-R-L-R wiggle
# (its start and end rounded ~1e-14 off the line turned every straight word's first arc negative).
ZERO = 1e-10

Segment = tuple[str, float]
Word = tuple[Segment, ...]


def mod2pi(a: float) -> float:
    """a wrapped into (-pi, pi]."""
    v = math.fmod(a, TWO_PI)
    if v < -PI:
        v += TWO_PI
    elif v > PI:
        v -= TWO_PI
    return v


def _tau_omega(u, v, xi, eta, phi):
    delta = mod2pi(u - v)
    a = math.sin(u) - math.sin(delta)
    b = math.cos(u) - math.cos(delta) - 1.0
    t1 = math.atan2(eta * a - xi * b, xi * a + eta * b)
    t2 = 2.0 * (math.cos(delta) - math.cos(v) - math.cos(u)) + 3.0
    tau = mod2pi(t1 + PI) if t2 < 0 else mod2pi(t1)
    return tau, mod2pi(tau - u + v - phi)


# --- base words: (x, y, phi) of the goal in the start frame (radius 1), with sin(phi) and cos(phi)
# -> the segments' signed lengths (their kinds are in _BASE) or None


def _lsl(x, y, phi, sp, cp):  # 8.1  L+ S+ L+
    xi, eta = x - sp, y - 1.0 + cp
    u, t = math.hypot(xi, eta), math.atan2(eta, xi)
    v = mod2pi(phi - t)
    if t >= -ZERO and v >= -ZERO:
        return t, u, v
    return None


def _lsr(x, y, phi, sp, cp):  # 8.2  L+ S+ R+
    xi, eta = x + sp, y - 1.0 - cp
    u1 = xi * xi + eta * eta
    if u1 < 4.0:
        return None
    u = math.sqrt(u1 - 4.0)
    t = mod2pi(math.atan2(eta, xi) + math.atan2(2.0, u))
    v = mod2pi(t - phi)
    if t >= -ZERO and v >= -ZERO:
        return t, u, v
    return None


def _lrl(x, y, phi, sp, cp):  # 8.3 / 8.4  L+ R- L
    xi, eta = x - sp, y - 1.0 + cp
    rho = math.hypot(xi, eta)
    if rho > 4.0:
        return None
    u = -2.0 * math.asin(0.25 * rho)
    t = mod2pi(math.atan2(eta, xi) + 0.5 * u + PI)
    v = mod2pi(phi - t + u)
    if t >= -ZERO and u <= ZERO:
        return t, u, v
    return None


def _lrlr_a(x, y, phi, sp, cp):  # 8.7  L+ R+u L-u R-
    xi, eta = x + sp, y - 1.0 - cp
    rho = 0.25 * (2.0 + math.hypot(xi, eta))
    if rho > 1.0:
        return None
    u = math.acos(rho)
    t, v = _tau_omega(u, -u, xi, eta, phi)
    if t >= -ZERO and v <= ZERO:
        return t, u, -u, v
    return None


def _lrlr_b(x, y, phi, sp, cp):  # 8.8  L+ R-u L-u R+
    xi, eta = x + sp, y - 1.0 - cp
    rho = (20.0 - xi * xi - eta * eta) / 16.0
    if not 0.0 <= rho <= 1.0:
        return None
    u = -math.acos(rho)
    if u < -HALF_PI:
        return None
    t, v = _tau_omega(u, u, xi, eta, phi)
    if t >= -ZERO and v >= -ZERO:
        return t, u, u, v
    return None


def _lrsl(x, y, phi, sp, cp):  # 8.9  L+ R-pi/2 S- L-
    xi, eta = x - sp, y - 1.0 + cp
    rho = math.hypot(xi, eta)
    if rho < 2.0:
        return None
    r = math.sqrt(rho * rho - 4.0)
    u = 2.0 - r
    t = mod2pi(math.atan2(eta, xi) + math.atan2(r, -2.0))
    v = mod2pi(phi - HALF_PI - t)
    if t >= -ZERO and u <= ZERO and v <= ZERO:
        return t, -HALF_PI, u, v
    return None


def _lrsr(x, y, phi, sp, cp):  # 8.10  L+ R-pi/2 S- R-
    xi, eta = x + sp, y - 1.0 - cp
    rho, t = math.hypot(-eta, xi), math.atan2(xi, -eta)
    if rho < 2.0:
        return None
    u = 2.0 - rho
    v = mod2pi(t + HALF_PI - phi)
    if t >= -ZERO and u <= ZERO and v <= ZERO:
        return t, -HALF_PI, u, v
    return None


def _lrslr(x, y, phi, sp, cp):  # 8.11  L+ R-pi/2 S- L-pi/2 R+
    xi, eta = x + sp, y - 1.0 - cp
    rho = math.hypot(xi, eta)
    if rho < 2.0:
        return None
    u = 4.0 - math.sqrt(rho * rho - 4.0)
    if u > ZERO:
        return None
    t = mod2pi(math.atan2((4.0 - u) * xi - 2.0 * eta, -2.0 * xi + (u - 4.0) * eta))
    v = mod2pi(t - phi)
    if t >= -ZERO and v >= -ZERO:
        return t, -HALF_PI, u, -HALF_PI, v
    return None


_SWAP = {"L": "R", "R": "L", "S": "S"}
# (base word, its segments' kinds, whether its "backwards" image is a distinct word: only the
# words that are not palindromic in shape need it)
_BASE = ((_lsl, "LSL", False), (_lsr, "LSR", False), (_lrl, "LRL", True), (_lrlr_a, "LRLR", False),
         (_lrlr_b, "LRLR", False), (_lrsl, "LRSL", True), (_lrsr, "LRSR", True), (_lrslr, "LRSLR", False))
# time flip negates lengths (the query's x), reflection swaps L and R (the query's y); phi flips
# sign when exactly one of them applies: (sign of x, sign of y, flip, mirror)
_SYMMETRIES = ((1.0, 1.0, False, False), (-1.0, 1.0, True, False), (1.0, -1.0, False, True), (-1.0, -1.0, True, True))


def word_length(word: Word) -> float:
    return sum(abs(s) for _, s in word)


def reeds_shepp_word(x: float, y: float, phi: float) -> Word:
    """The shortest Reeds-Shepp word to (x, y, phi) in the start frame, radius 1.

    The base words return bare lengths and the winner alone becomes a word: this runs once per
    nearest-neighbour candidate, and building ~30 words of tuples per query cost a third of it.
    """
    best, best_len = None, math.inf
    sp, cp = math.sin(phi), math.cos(phi)
    xb, yb = x * cp + y * sp, x * sp - y * cp
    for base, kinds, backwards in _BASE:
        for gx, gy, reverse in ((x, y, False), (xb, yb, True)) if backwards else ((x, y, False),):
            for sx, sy, flip, mirror in _SYMMETRIES:
                same = flip == mirror  # sin(-phi) = -sin(phi): one sine serves every query
                lengths = base(sx * gx, sy * gy, phi if same else -phi, sp if same else -sp, cp)
                if lengths is None:
                    continue
                length = sum(map(abs, lengths))
                if length < best_len:
                    best, best_len = (kinds, lengths, reverse, flip, mirror), length
    kinds, lengths, reverse, flip, mirror = best
    word = tuple(zip(kinds, lengths))
    if reverse:
        word = word[::-1]
    if flip:
        word = tuple((k, -s) for k, s in word)
    if mirror:
        word = tuple((_SWAP[k], s) for k, s in word)
    return word


def _arc(a: float) -> float:
    """a wrapped into [0, 2 pi), with a rounding error just below 2 pi read as 0 (a turn of nothing)."""
    v = a % TWO_PI
    return 0.0 if TWO_PI - v < 1e-10 else v


def dubins_word(x: float, y: float, phi: float) -> Word:
    """The shortest Dubins (forwards only) word to (x, y, phi) in the start frame, radius 1."""
    d, theta = math.hypot(x, y), math.atan2(y, x)
    a, b = _arc(-theta), _arc(phi - theta)
    sa, sb, ca, cb, cab = math.sin(a), math.sin(b), math.cos(a), math.cos(b), math.cos(a - b)
    words = []
    p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sa - sb)  # LSL
    if p2 >= -1e-10:  # rounding: a straight of length 0 can come out as sqrt(-1e-16)
        p2 = max(p2, 0.0)
        tmp = math.atan2(cb - ca, d + sa - sb)
        words.append((("L", _arc(tmp - a)), ("S", math.sqrt(p2)), ("L", _arc(b - tmp))))
    p2 = 2.0 + d * d - 2.0 * cab + 2.0 * d * (sb - sa)  # RSR
    if p2 >= -1e-10:  # rounding: a straight of length 0 can come out as sqrt(-1e-16)
        p2 = max(p2, 0.0)
        tmp = math.atan2(ca - cb, d - sa + sb)
        words.append((("R", _arc(a - tmp)), ("S", math.sqrt(p2)), ("R", _arc(tmp - b))))
    p2 = -2.0 + d * d + 2.0 * cab + 2.0 * d * (sa + sb)  # LSR
    if p2 >= -1e-10:  # rounding: a straight of length 0 can come out as sqrt(-1e-16)
        p2 = max(p2, 0.0)
        p = math.sqrt(p2)
        tmp = math.atan2(-ca - cb, d + sa + sb) - math.atan2(-2.0, p)
        words.append((("L", _arc(tmp - a)), ("S", p), ("R", _arc(tmp - b))))
    p2 = -2.0 + d * d + 2.0 * cab - 2.0 * d * (sa + sb)  # RSL
    if p2 >= -1e-10:  # rounding: a straight of length 0 can come out as sqrt(-1e-16)
        p2 = max(p2, 0.0)
        p = math.sqrt(p2)
        tmp = math.atan2(ca + cb, d - sa - sb) - math.atan2(2.0, p)
        words.append((("R", _arc(a - tmp)), ("S", p), ("L", _arc(b - tmp))))
    c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sa - sb)) / 8.0  # RLR
    if abs(c) <= 1.0 + 1e-10:
        c = min(1.0, max(-1.0, c))
        p = _arc(TWO_PI - math.acos(c))
        t = _arc(a - math.atan2(ca - cb, d - sa + sb) + 0.5 * p)
        words.append((("R", t), ("L", p), ("R", _arc(a - b - t + p))))
    c = (6.0 - d * d + 2.0 * cab + 2.0 * d * (sb - sa)) / 8.0  # LRL
    if abs(c) <= 1.0 + 1e-10:
        c = min(1.0, max(-1.0, c))
        p = _arc(TWO_PI - math.acos(c))
        t = _arc(-a - math.atan2(ca - cb, d + sa - sb) + 0.5 * p)
        words.append((("L", t), ("R", p), ("L", _arc(b - a - t + p))))
    return min((_merge(w) for w in words), key=word_length)


def _merge(word: Word) -> Word:
    """A Dubins word whose straight came out as (nearly) nothing, as one arc.

    With a straight of length ~0 the split of the turn between the two arcs is an atan2 of a
    ~zero vector, and the two arcs may sum to a needless extra full circle."""
    (k1, t), (k2, p), (k3, q) = word
    if k2 == "S" and k1 == k3 and p < 1e-7:
        return ((k1, _arc(t + q)),)
    return word


def prefix(word: Word, length: float) -> Word:
    """The first ``length`` (same units as the word) of ``word``."""
    out, left = [], length
    for kind, s in word:
        if left <= 0.0:
            break
        out.append((kind, math.copysign(min(abs(s), left), s)))
        left -= abs(s)
    return tuple(out)


def relative(a, b, radius: float) -> tuple[float, float, float]:
    """b in a's frame, positions divided by ``radius``."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy) / radius, (-s * dx + c * dy) / radius, b[2] - a[2]


def advance(x: float, y: float, th: float, kind: str, s: float) -> tuple[float, float, float]:
    """The pose after driving signed length ``s`` (radius 1) of a segment from (x, y, th)."""
    if kind == "S":
        return x + s * math.cos(th), y + s * math.sin(th), th
    if kind == "L":
        return x + math.sin(th + s) - math.sin(th), y - math.cos(th + s) + math.cos(th), th + s
    return x - math.sin(th - s) + math.sin(th), y + math.cos(th - s) - math.cos(th), th - s
