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

The Reeds-Shepp solver is compiled (numba; one query evaluates ~50 closed forms: ~34 us in Python, a few in
numba, the car planner's largest cost per iteration on the generated lots, #33). Its numbers are Python's: the
same libm calls in the same order, and :func:`hypot` is CPython's correctly rounded ``math.hypot`` (libm's
differs in the last bit in ~0.3 % of calls). Compiled code sees a word as rows (turn, signed length), turn +1
for L, -1 for R, 0 for S (:data:`TURN`); :func:`reeds_shepp_word` gives the tuple form.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from lazyground.user_cache import use_kernel_cache

use_kernel_cache()  # before any kernel is defined: caches keyed by every kernel file's text

PI = math.pi
TWO_PI = 2.0 * math.pi
HALF_PI = 0.5 * math.pi
# A length this close to 0 still counts as having its sign. OMPL's 10 ulp of a unit is too tight for poses tens of
# radii from the origin: a 0.1 m straight piece of a dense path, re-solved, came out a 0.23 m L-R-L-R wiggle
# (its start and end rounded ~1e-14 off the line turned every straight word's first arc negative).
ZERO = 1e-10
_DBL_MIN = 2.2250738585072014e-308
MAX_SEGMENTS = 5  # the longest Reeds-Shepp word (C C|S C C)

Segment = tuple[str, float]
Word = tuple[Segment, ...]
TURN = {"L": 1.0, "R": -1.0, "S": 0.0}  # a segment's heading change per unit of arc
KIND = {1.0: "L", -1.0: "R", 0.0: "S"}


@njit(cache=True)
def mod2pi(a: float) -> float:
    """a wrapped into (-pi, pi]."""
    v = np.fmod(a, TWO_PI)  # (C's fmod, exact: math.fmod's numbers)
    if v < -PI:
        v += TWO_PI
    elif v > PI:
        v -= TWO_PI
    return v


@njit(cache=True)
def _two_product(a, b):
    """a b as hi + lo exactly (Dekker's split: the numbers of fma(a, b, -a b))."""
    p = a * b
    t = 134217729.0 * a
    ahi = t - (t - a)
    alo = a - ahi
    t = 134217729.0 * b
    bhi = t - (t - b)
    blo = b - bhi
    return p, ((ahi * bhi - p) + ahi * blo + alo * bhi) + alo * blo


@njit(cache=True)
def hypot(a: float, b: float) -> float:
    """CPython's math.hypot of two numbers (its ``vector_norm``: scaled, compensated sums, one Newton step),
    bit for bit; libm's hypot, numba's, is not."""
    a, b = abs(a), abs(b)
    m = max(a, b)
    if math.isinf(m):
        return m
    if math.isnan(a) or math.isnan(b):
        return math.nan
    if m == 0.0:
        return m
    e = math.frexp(m)[1]
    if e < -1023:  # (subnormal: CPython rescales; not a car's numbers)
        return _DBL_MIN * hypot(a / _DBL_MIN, b / _DBL_MIN)
    scale = math.ldexp(1.0, -e)
    csum, frac1, frac2 = 1.0, 0.0, 0.0
    for x in (a * scale, b * scale):
        hi, lo = _two_product(x, x)
        s = csum + hi
        frac2 += (csum - s) + hi
        csum = s
        frac1 += lo
    h = math.sqrt(csum - 1.0 + (frac1 + frac2))
    hi, lo = _two_product(-h, h)
    s = csum + hi
    frac2 += (csum - s) + hi
    csum = s
    frac1 += lo
    x = csum - 1.0 + (frac1 + frac2)
    h += x / (2.0 * h)
    return h / scale


@njit(cache=True)
def _tau_omega(u, v, xi, eta, phi):
    delta = mod2pi(u - v)
    a = math.sin(u) - math.sin(delta)
    b = math.cos(u) - math.cos(delta) - 1.0
    t1 = math.atan2(eta * a - xi * b, xi * a + eta * b)
    t2 = 2.0 * (math.cos(delta) - math.cos(v) - math.cos(u)) + 3.0
    tau = mod2pi(t1 + PI) if t2 < 0 else mod2pi(t1)
    return tau, mod2pi(tau - u + v - phi)


# --- base words: (x, y, phi) of the goal in the start frame (radius 1), with sin(phi) and cos(phi)
# -> the segments' signed lengths in ``out`` (their kinds are in _KINDS), how many (0: no such word)


@njit(cache=True)
def _lsl(x, y, phi, sp, cp, out):  # 8.1  L+ S+ L+
    xi, eta = x - sp, y - 1.0 + cp
    u, t = hypot(xi, eta), math.atan2(eta, xi)
    v = mod2pi(phi - t)
    if t >= -ZERO and v >= -ZERO:
        out[0], out[1], out[2] = t, u, v
        return 3
    return 0


@njit(cache=True)
def _lsr(x, y, phi, sp, cp, out):  # 8.2  L+ S+ R+
    xi, eta = x + sp, y - 1.0 - cp
    u1 = xi * xi + eta * eta
    if u1 < 4.0:
        return 0
    u = math.sqrt(u1 - 4.0)
    t = mod2pi(math.atan2(eta, xi) + math.atan2(2.0, u))
    v = mod2pi(t - phi)
    if t >= -ZERO and v >= -ZERO:
        out[0], out[1], out[2] = t, u, v
        return 3
    return 0


@njit(cache=True)
def _lrl(x, y, phi, sp, cp, out):  # 8.3 / 8.4  L+ R- L
    xi, eta = x - sp, y - 1.0 + cp
    rho = hypot(xi, eta)
    if rho > 4.0:
        return 0
    u = -2.0 * math.asin(0.25 * rho)
    t = mod2pi(math.atan2(eta, xi) + 0.5 * u + PI)
    v = mod2pi(phi - t + u)
    if t >= -ZERO and u <= ZERO:
        out[0], out[1], out[2] = t, u, v
        return 3
    return 0


@njit(cache=True)
def _lrlr_a(x, y, phi, sp, cp, out):  # 8.7  L+ R+u L-u R-
    xi, eta = x + sp, y - 1.0 - cp
    rho = 0.25 * (2.0 + hypot(xi, eta))
    if rho > 1.0:
        return 0
    u = math.acos(rho)
    t, v = _tau_omega(u, -u, xi, eta, phi)
    if t >= -ZERO and v <= ZERO:
        out[0], out[1], out[2], out[3] = t, u, -u, v
        return 4
    return 0


@njit(cache=True)
def _lrlr_b(x, y, phi, sp, cp, out):  # 8.8  L+ R-u L-u R+
    xi, eta = x + sp, y - 1.0 - cp
    rho = (20.0 - xi * xi - eta * eta) / 16.0
    if not 0.0 <= rho <= 1.0:
        return 0
    u = -math.acos(rho)
    if u < -HALF_PI:
        return 0
    t, v = _tau_omega(u, u, xi, eta, phi)
    if t >= -ZERO and v >= -ZERO:
        out[0], out[1], out[2], out[3] = t, u, u, v
        return 4
    return 0


@njit(cache=True)
def _lrsl(x, y, phi, sp, cp, out):  # 8.9  L+ R-pi/2 S- L-
    xi, eta = x - sp, y - 1.0 + cp
    rho = hypot(xi, eta)
    if rho < 2.0:
        return 0
    r = math.sqrt(rho * rho - 4.0)
    u = 2.0 - r
    t = mod2pi(math.atan2(eta, xi) + math.atan2(r, -2.0))
    v = mod2pi(phi - HALF_PI - t)
    if t >= -ZERO and u <= ZERO and v <= ZERO:
        out[0], out[1], out[2], out[3] = t, -HALF_PI, u, v
        return 4
    return 0


@njit(cache=True)
def _lrsr(x, y, phi, sp, cp, out):  # 8.10  L+ R-pi/2 S- R-
    xi, eta = x + sp, y - 1.0 - cp
    rho, t = hypot(-eta, xi), math.atan2(xi, -eta)
    if rho < 2.0:
        return 0
    u = 2.0 - rho
    v = mod2pi(t + HALF_PI - phi)
    if t >= -ZERO and u <= ZERO and v <= ZERO:
        out[0], out[1], out[2], out[3] = t, -HALF_PI, u, v
        return 4
    return 0


@njit(cache=True)
def _lrslr(x, y, phi, sp, cp, out):  # 8.11  L+ R-pi/2 S- L-pi/2 R+
    xi, eta = x + sp, y - 1.0 - cp
    rho = hypot(xi, eta)
    if rho < 2.0:
        return 0
    u = 4.0 - math.sqrt(rho * rho - 4.0)
    if u > ZERO:
        return 0
    t = mod2pi(math.atan2((4.0 - u) * xi - 2.0 * eta, -2.0 * xi + (u - 4.0) * eta))
    v = mod2pi(t - phi)
    if t >= -ZERO and v >= -ZERO:
        out[0], out[1], out[2], out[3], out[4] = t, -HALF_PI, u, -HALF_PI, v
        return 5
    return 0


# the base words in the order they are tried (ties: the first wins), their segments' turns (padded with 0),
# and whether their "backwards" image is a distinct word: only the words that are not palindromic in shape need it
_BASES = ("LSL", "LSR", "LRL", "LRLR", "LRLR", "LRSL", "LRSR", "LRSLR")
_KINDS = np.array([[TURN[k] for k in w] + [0.0] * (MAX_SEGMENTS - len(w)) for w in _BASES])
_BACKWARDS = np.array([False, False, True, False, False, True, True, False])


@njit(cache=True)
def _base(k, x, y, phi, sp, cp, out):
    """Base word k's lengths into ``out``: how many (0: none)."""
    if k == 0:
        return _lsl(x, y, phi, sp, cp, out)
    if k == 1:
        return _lsr(x, y, phi, sp, cp, out)
    if k == 2:
        return _lrl(x, y, phi, sp, cp, out)
    if k == 3:
        return _lrlr_a(x, y, phi, sp, cp, out)
    if k == 4:
        return _lrlr_b(x, y, phi, sp, cp, out)
    if k == 5:
        return _lrsl(x, y, phi, sp, cp, out)
    if k == 6:
        return _lrsr(x, y, phi, sp, cp, out)
    return _lrslr(x, y, phi, sp, cp, out)


@njit(cache=True)
def reeds_shepp(x: float, y: float, phi: float, out: np.ndarray) -> int:
    """The shortest Reeds-Shepp word to (x, y, phi) in the start frame, radius 1, into ``out`` (rows (turn,
    signed length), at least MAX_SEGMENTS of them): how many segments.

    Every base word is tried under the symmetries: time flip (drive it backwards: negate the query's x and
    the lengths), reflection (swap left and right: negate the query's y and the turns), phi's sign flipping
    when exactly one applies; and read end to start where that is a distinct word (the query rotated into the
    goal's frame). A word's length sums its segments in base order; the first shortest wins.
    """
    sp, cp = math.sin(phi), math.cos(phi)
    xb, yb = x * cp + y * sp, x * sp - y * cp
    lengths, best = np.empty(MAX_SEGMENTS), np.empty(MAX_SEGMENTS)
    best_len, best_k, best_n, best_code = math.inf, -1, 0, 0
    for k in range(len(_BASES)):
        for reverse in range(2 if _BACKWARDS[k] else 1):
            gx, gy = (xb, yb) if reverse else (x, y)
            for code in range(4):  # (flip, mirror) = (code & 1, code >> 1)
                flip, mirror = code & 1, code >> 1
                same = flip == mirror  # sin(-phi) = -sin(phi): one sine serves every query
                n = _base(k, -gx if flip else gx, -gy if mirror else gy, phi if same else -phi,
                          sp if same else -sp, cp, lengths)
                if n == 0:
                    continue
                length = 0.0
                for i in range(n):
                    length += abs(lengths[i])
                if length < best_len:
                    best_len, best_k, best_n, best_code = length, k, n, code + 4 * reverse
                    best[:n] = lengths[:n]
    if best_k < 0:
        return 0
    flip, mirror, reverse = best_code & 1, (best_code >> 1) & 1, best_code >> 2
    for i in range(best_n):
        j = best_n - 1 - i if reverse else i
        out[i, 0] = -_KINDS[best_k, j] if mirror else _KINDS[best_k, j]
        out[i, 1] = -best[j] if flip else best[j]
    return best_n


def word_length(word: Word) -> float:
    return sum(abs(s) for _, s in word)


def reeds_shepp_word(x: float, y: float, phi: float) -> Word:
    """The shortest Reeds-Shepp word to (x, y, phi) in the start frame, radius 1 (:func:`reeds_shepp`)."""
    out = np.empty((MAX_SEGMENTS, 2))
    n = reeds_shepp(float(x), float(y), float(phi), out)
    return tuple((KIND[t], s) for t, s in out[:n].tolist())


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
