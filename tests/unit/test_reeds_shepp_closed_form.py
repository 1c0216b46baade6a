"""Reeds-Shepp lengths checked without OMPL: cases whose shortest length is proved by hand, and each word
family's closed form given the end pose of a word built from chosen segment lengths.

Lengths are in turning radii. Two lower bounds hold for any car path: its length is at least the straight
distance between its ends, and at least the turn it makes (an arc of length s turns the heading by s, a straight
by nothing), i.e. |phi| wrapped to [0, pi].
"""

import cmath
import math

import numpy as np
import pytest

from lazyground.planning import curves
from lazyground.planning.kinematics import make_space
from lazyground.planning.space import ConfigSpace

TURN = {"L": 1, "R": -1}


def drive(word):
    """The end pose of a word from the origin, by rotating the position about each arc's centre (complex numbers;
    not the solver's own stepping): a left arc's centre is one radius to the left of the heading."""
    p, th = 0j, 0.0
    for kind, s in word:
        if kind == "S":
            p += s * cmath.exp(1j * th)
            continue
        side = TURN[kind]
        centre = p + side * 1j * cmath.exp(1j * th)
        p = centre + (p - centre) * cmath.exp(1j * side * s)
        th += side * s
    return p.real, p.imag, curves.mod2pi(th)


def rs(x, y, phi):
    return curves.word_length(curves.reeds_shepp_word(x, y, phi))


@pytest.mark.parametrize("d", [0.5, 3.0, 12.0])
def test_straight_ahead_or_back_is_its_distance(d):
    assert rs(d, 0.0, 0.0) == pytest.approx(d)
    assert rs(-d, 0.0, 0.0) == pytest.approx(d)
    assert [(k, round(s, 9)) for k, s in curves.reeds_shepp_word(-d, 0.0, 0.0) if abs(s) > 1e-12] == [("S", -d)]


@pytest.mark.parametrize("phi", [0.3, 1.0, math.pi / 2, 2.5, math.pi])
@pytest.mark.parametrize("kind, gear", [("L", 1), ("R", 1), ("L", -1), ("R", -1)])
def test_one_arc_is_the_turn_it_makes(phi, kind, gear):
    """One arc of turn phi <= pi, in either gear and direction: its length phi is the turn lower bound, so no word
    is shorter (a half circle to (0, 2, pi) included)."""
    x, y, th = drive(((kind, gear * phi),))
    assert rs(x, y, th) == pytest.approx(phi, abs=1e-9)


def test_a_u_turn_is_a_half_circle():
    assert rs(0.0, 2.0, math.pi) == pytest.approx(math.pi)
    assert rs(0.0, -2.0, math.pi) == pytest.approx(math.pi)


# (base closed form, the word's kinds, chosen signed lengths in its domain)
FAMILIES = [
    (curves._lsl, "LSL", (0.7, 2.0, 1.1)),  # CSC, 8.1
    (curves._lsr, "LSR", (0.5, 1.5, 0.8)),  # CSC, 8.2
    (curves._lrl, "LRL", (0.8, -1.2, 0.5)),  # CCC, 8.3
    (curves._lrl, "LRL", (0.6, -0.9, -0.4)),  # CCC, 8.4
    (curves._lrlr_a, "LRLR", (0.3, 0.9, -0.9, -0.4)),  # CCCC, 8.7
    (curves._lrlr_b, "LRLR", (0.4, -0.7, -0.7, 0.6)),  # CCCC, 8.8
    (curves._lrsl, "LRSL", (0.5, -math.pi / 2, -1.0, -0.3)),  # CCSC, 8.9
    (curves._lrsr, "LRSR", (0.6, -math.pi / 2, -1.2, -0.4)),  # CCSC, 8.10
    (curves._lrslr, "LRSLR", (0.3, -math.pi / 2, -0.8, -math.pi / 2, 0.5)),  # CCSCC, 8.11
]


@pytest.mark.parametrize("base, kinds, lengths", FAMILIES, ids=[f"{k}{i}" for i, (_, k, _) in enumerate(FAMILIES)])
def test_each_closed_form_recovers_the_word_it_is_given_the_end_of(base, kinds, lengths):
    """Drive a word of the family, hand its end to the family's closed form: it returns the same lengths. The
    shortest word over all families is no longer, and no shorter than the two lower bounds."""
    word = tuple(zip(kinds, lengths))
    x, y, phi = drive(word)
    out = np.empty(curves.MAX_SEGMENTS)
    n = base(x, y, phi, math.sin(phi), math.cos(phi), out)
    assert n == len(lengths) and np.allclose(out[:n], lengths, atol=1e-9)
    best = rs(x, y, phi)
    assert best <= sum(map(abs, lengths)) + 1e-9
    assert best >= max(math.hypot(x, y), abs(phi)) - 1e-9
    assert np.allclose(drive(curves.reeds_shepp_word(x, y, phi)), (x, y, phi), atol=1e-9)


def test_a_long_csc_is_its_arcs_plus_its_straight():
    """Quarter turn left, d straight, quarter turn left reaches (0, 2 + d, pi) in pi + d; the shortest word is
    that long and its arcs turn exactly pi, the least the turn bound allows (a CSC word, not a longer CCC)."""
    for d in (2.0, 5.0, 10.0):
        word = curves.reeds_shepp_word(0.0, 2.0 + d, math.pi)
        assert curves.word_length(word) == pytest.approx(math.pi + d)
        assert sum(abs(s) for k, s in word if k != "S") == pytest.approx(math.pi)


def test_car_space_lengths_are_in_metres():
    """On a car space of radius 3.86 m (reference point on the origin), the cases above scale by the radius."""
    base = ConfigSpace(("x", "y", "th"), np.array([-50.0, -50.0, -np.pi]), np.array([50.0, 50.0, np.pi]), None,
                       np.array([False, False, True]))
    space, r = make_space(base, "reeds-shepp", 3.86), 3.86
    a = np.array([1.0, 2.0, 0.4])
    ahead = a + [7.0 * math.cos(0.4), 7.0 * math.sin(0.4), 0.0]
    assert space.distance(a, ahead) == pytest.approx(7.0)
    quarter = a + [r * (math.sin(0.4 + math.pi / 2) - math.sin(0.4)), r * (math.cos(0.4) - math.cos(0.4 + math.pi / 2)),
                   math.pi / 2]
    assert space.distance(a, quarter) == pytest.approx(r * math.pi / 2)
    u_turn = np.array([0.0, 2 * r + 5.0, math.pi])
    assert space.distance(np.zeros(3), u_turn) == pytest.approx(r * math.pi + 5.0)
