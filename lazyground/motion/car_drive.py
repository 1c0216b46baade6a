"""A car's path as it can be driven: curvature made continuous, heading always along the motion.

A planned car path is dense along Reeds-Shepp (or Dubins) curves: arcs of the minimum turning
radius and straight lines, the curvature jumping where they meet. A car cannot drive such a
jump without stopping (its heading rate would jump, an infinite heading acceleration), so
within each gear segment the curvature (heading change per metre of the rear axle) is
averaged over a window of ``window`` metres (mirrored at the segment's ends, so it turns by
as much in all). The averaged curvature is continuous, piecewise linear and never above the
curves' (|kappa| <= 1 / radius), and the car drives it exactly (its rear axle moves along
its heading, it does not slide). Averaging cuts corners (up to ~15 cm per metre of window on
a lane change) and moves the segment's end by centimetres; a small correction of the
curvature, made only where it is below the maximum (so it stays within the turning radius)
and solved by Newton's method, brings it back onto the planned end pose. Where that fails
(segments at full lock from left to right leave it no room) a smaller window is tried, then
the segment is split at a curvature jump (the car stops there) and each part tried alike;
parts without room keep their exact curves. The result leaves the planned curves, so the
caller checks it for collisions; ``window`` 0 keeps the exact curves throughout.

The curve is represented on a grid of about GRID metres: curvature linear between the nodes,
heading its exact integral, positions by the chord of each step.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lazyground.planning.car import CarSpace, drive_profile

GRID = 0.025  # m between the nodes of a driven curve (and of its timing)
MIN_NODES = 5  # a short curve too: timed from rest to rest it needs nodes between its ends
NEWTON_STEPS = 12
END_TOLERANCE = 1e-10  # m and rad: how close a corrected curve ends to the planned pose
# the end correction: the room to turn (1 - |kappa| r) times Legendre polynomials of degree < BASIS along the
# segment (3 and 6 succeeded on as many segments of the parking plans; 10 on fewer)
BASIS = 3


@dataclass(frozen=True)
class Drive:
    """One gear segment as driven: the rear axle's arc length ``s`` at the nodes, curvature, heading
    and position there, the direction of travel (+1 / -1) and the body origin's distance ahead of the
    rear axle (``ahead``)."""

    s: np.ndarray
    kappa: np.ndarray
    theta: np.ndarray
    p: np.ndarray  # (n, 2) rear axle
    gear: float
    ahead: float
    window: float = 0.0  # the curvature averaging it was made with (0: an exact planned curve)

    @property
    def length(self) -> float:
        return float(self.s[-1])

    def derivatives(self, s: np.ndarray, right: bool = True):
        """Body coordinates q(s), dq/ds and d2q/ds2 (x, y, unwrapped heading) at arc lengths ``s``.

        d2q/ds2 uses the curvature slope of the step on the right of a node (``right``), else of the
        step on its left.
        """
        s = np.clip(np.asarray(s, float), 0.0, self.length)
        n = len(self.s) - 1
        k = np.clip(np.searchsorted(self.s, s, side="right" if right else "left") - 1, 0, n - 1)
        h = self.s[k + 1] - self.s[k]
        d = s - self.s[k]
        slope = (self.kappa[k + 1] - self.kappa[k]) / h
        kappa = self.kappa[k] + slope * d
        turned = self.kappa[k] * d + 0.5 * slope * d**2
        theta = self.theta[k] + turned
        p = self.p[k] + _chord(self.gear, d, turned, self.theta[k])
        e = np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        nrm = np.stack([-e[:, 1], e[:, 0]], axis=-1)
        b, g = self.ahead, self.gear
        q = np.column_stack([p + b * e, theta])
        d1 = np.column_stack([g * e + (b * kappa)[:, None] * nrm, kappa])
        d2 = np.column_stack([(g * kappa)[:, None] * nrm + b * (slope[:, None] * nrm - (kappa**2)[:, None] * e), slope])
        return q, d1, d2


def _chord(gear: float, d: np.ndarray, turned: np.ndarray, theta0: np.ndarray) -> np.ndarray:
    """The rear axle's displacement over d metres turning by ``turned``: the chord of that arc (exact on arcs
    and lines; on the linear-curvature ramps a close approximation, the curve's definition there)."""
    mid = theta0 + 0.5 * turned
    length = d * np.sinc(turned / (2.0 * np.pi))  # 2 sin(turned / 2) / turned * d
    return (gear * length)[..., None] * np.stack([np.cos(mid), np.sin(mid)], axis=-1)


def segment_steps(space: CarSpace, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """Per moving step of a dense gear segment (body coordinates, unwrapped heading): metres driven by the
    rear axle, the curvature (heading change per metre), the segment's direction of travel, and the
    sample each step starts from."""
    ref = space.reference(q)
    turn = np.diff(ref[:, 2])
    chord = np.hypot(*np.diff(ref[:, :2], axis=0).T)
    length = np.where(np.abs(turn) > 1e-9, space.radius * np.abs(turn), chord)
    gears = drive_profile(ref)
    moving = np.flatnonzero(length > 1e-9)
    if len(moving) and np.any(gears[moving] != gears[moving[0]]):
        raise ValueError("a gear segment changes direction of travel")
    gear = float(gears[moving[0]]) if len(moving) else 1.0
    return length[moving], turn[moving] / length[moving], gear, moving


def drives(space: CarSpace, q: np.ndarray, window: float) -> list[Drive]:
    """The gear segment ``q`` (dense, body coordinates, unwrapped heading) as driven curves.

    The whole segment is averaged when its end correction succeeds (with ``window``, else half or a
    quarter of it); else it is split (the car stopping there) at the curvature jump nearest its
    middle and each half tried alike, down to stretches shorter than two windows, which keep their
    exact curves.

    Args:
        space: the car space it was planned in (turning radius, rear axle offset).
        q: (n, 3) samples of one gear segment.
        window: metres the curvature is averaged over; 0: the exact curves, one Drive per
            stretch of constant curvature.

    Returns:
        The Drives, one after another from q[0] to q[-1] (the car rests between them); empty when
        q does not move.
    """
    lengths, kappa, gear, first = segment_steps(space, q)
    ref = space.reference(q)
    bounds = np.concatenate([[0.0], np.cumsum(lengths)])
    ahead = -space.offset

    def part(a: int, b: int) -> list[Drive]:
        """Steps a .. b - 1."""
        jumps = a + 1 + np.flatnonzero(np.abs(np.diff(kappa[a:b])) > 1e-9)
        if not len(jumps):
            nodes = _nodes(bounds[b] - bounds[a])
            return [_integrated(ref[first[a]], nodes, np.full(len(nodes), kappa[a]), gear, ahead)]
        for w in (window, 0.5 * window, 0.25 * window) if window > 0.0 else ():
            if bounds[b] - bounds[a] < 2.0 * w:
                continue
            drive = _smoothed(space, ref[first[a]], ref[first[b - 1] + 1], bounds[a : b + 1] - bounds[a],
                              kappa[a:b], gear, w)
            if drive is not None:
                return [replace(drive, window=w)]
        cut = jumps[np.argmin(np.abs(bounds[jumps] - 0.5 * (bounds[a] + bounds[b])))]
        return part(a, cut) + part(cut, b)

    return part(0, len(lengths)) if len(lengths) else []


def _nodes(length: float) -> np.ndarray:
    return np.linspace(0.0, length, max(MIN_NODES, int(np.ceil(length / GRID)) + 1))


def _integrated(start: np.ndarray, s: np.ndarray, kappa: np.ndarray, gear: float, ahead: float) -> Drive:
    """The curve of curvature ``kappa`` (linear between the nodes ``s``) driven from the rear axle pose ``start``."""
    h = np.diff(s)
    turned = 0.5 * h * (kappa[:-1] + kappa[1:])
    theta = start[2] + np.concatenate([[0.0], np.cumsum(turned)])
    steps = _chord(gear, h, turned, theta[:-1])
    p = start[:2] + np.vstack([np.zeros((1, 2)), np.cumsum(steps, axis=0)])
    return Drive(s, kappa, theta, p, gear, ahead)


def _averaged(bounds: np.ndarray, kappa: np.ndarray, s: np.ndarray, window: float) -> np.ndarray:
    """The curvature averaged over [s - window / 2, s + window / 2], mirrored beyond the segment's ends.

    Mirrored (kappa(-u) = kappa(u), kappa(S + u) = kappa(S - u)), the average turns by exactly as much
    as the segment; continuing the end curvatures instead turned a segment ending in a short arc
    0.05 rad too far (its end 1.3 m off on a 27 m segment, beyond the correction).
    """
    turned = np.concatenate([[0.0], np.cumsum(kappa * np.diff(bounds))])
    length, total = bounds[-1], turned[-1]
    # the cumulative turn K is point-mirrored about both ends: K(-u) = -K(u), K(S + u) = 2 K(S) - K(S - u)
    x = np.concatenate([-bounds[:0:-1], bounds, 2.0 * length - bounds[-2::-1]])
    y = np.concatenate([-turned[:0:-1], turned, 2.0 * total - turned[-2::-1]])

    def cumulative(at):
        # beyond a mirrored copy (a window longer than the segment) the turn continues linearly
        return np.interp(at, x, y, left=np.nan, right=np.nan)

    half = min(0.5 * window, length)
    return (cumulative(s + half) - cumulative(s - half)) / (2.0 * half)


def _smoothed(space: CarSpace, start, end, bounds, kappa, gear, window) -> Drive | None:
    """The averaged curve, corrected to end on ``end``; None if the correction does not converge or
    would turn tighter than the radius."""
    s = _nodes(bounds[-1])
    base = _averaged(bounds, kappa, s, window)
    ahead = -space.offset
    # corrections go where the curve turns less than it may: (1 - |kappa| r) x Legendre polynomials of xi in [-1, 1]
    xi = 2.0 * s / s[-1] - 1.0
    room = np.clip(1.0 - np.abs(base) * space.radius, 0.0, 1.0)
    basis = room * np.polynomial.legendre.legvander(xi, BASIS - 1).T
    target = end.copy()

    def miss(c):
        drive = _integrated(start, s, base + c @ basis, gear, ahead)
        return drive, np.array([*(drive.p[-1] - target[:2]), drive.theta[-1] - target[2]])

    c = np.zeros(len(basis))
    drive, r = miss(c)
    for _ in range(NEWTON_STEPS):
        if np.max(np.abs(r)) <= END_TOLERANCE:
            break
        eps = 1e-7
        jac = np.column_stack([(miss(c + eps * e)[1] - r) / eps for e in np.eye(len(c))])
        step = np.linalg.lstsq(jac, r, rcond=None)[0]  # the smallest step that meets the end (to first order)
        for _ in range(6):  # halved until it brings the end closer (the map is far from linear at times)
            tried, r_new = miss(c - step)
            if np.max(np.abs(r_new)) < np.max(np.abs(r)):
                break
            step = 0.5 * step
        else:
            return None
        c, drive, r = c - step, tried, r_new
    if np.max(np.abs(r)) > END_TOLERANCE or np.max(np.abs(drive.kappa)) * space.radius > 1.0 + 1e-9:
        return None
    return drive

