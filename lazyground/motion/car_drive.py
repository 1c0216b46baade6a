"""A car's path as it can be driven: curvature made continuous, heading always along the motion.

A planned car path is dense along Reeds-Shepp (or Dubins) curves: arcs of the minimum turning
radius and straight lines, the curvature jumping where they meet. A car cannot drive such a
jump without stopping (its heading rate would jump, an infinite heading acceleration), so
within each gear segment the curvature (heading change per metre of the rear axle) is
averaged over a window of ``window`` metres. The averaged curvature is continuous, piecewise
linear and never above the curves' (|kappa| <= 1 / radius), and the car drives it exactly
(its rear axle moves along its heading, it does not slide). Averaging moves the segment's end
by a few centimetres; a small correction of the curvature, made only where it is below the
maximum (so it stays within the turning radius) and solved by Newton's method, brings it back
onto the planned end pose. The result deviates from the planned curves by centimetres, so the
caller checks it for collisions; ``window`` 0 keeps the exact curves, split where the
curvature jumps (the car stops there).

The curve is represented on a grid of about GRID metres: curvature linear between the nodes,
heading its exact integral, positions by the chord of each step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.geometry import wrap_angle
from lazyground.planning.car import CarSpace, drive_profile

GRID = 0.025  # m between the nodes of a driven curve (and of its timing)
NEWTON_STEPS = 8
END_TOLERANCE = 1e-10  # m and rad: how close a corrected curve ends to the planned pose


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


def segment_steps(space: CarSpace, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """Per step of a dense gear segment (body coordinates, unwrapped heading): metres driven by the
    rear axle, the curvature (heading change per metre) and the segment's direction of travel."""
    ref = space.reference(q)
    turn = np.diff(ref[:, 2])
    chord = np.hypot(*np.diff(ref[:, :2], axis=0).T)
    length = np.where(np.abs(turn) > 1e-9, space.radius * np.abs(turn), chord)
    gears = drive_profile(ref)
    if np.any(gears[length > 1e-9] != gears[np.argmax(length)]):
        raise ValueError("a gear segment changes direction of travel")
    moving = length > 1e-9
    return length[moving], turn[moving] / length[moving], float(gears[np.argmax(length)])


def drives(space: CarSpace, q: np.ndarray, window: float) -> list[Drive]:
    """The gear segment ``q`` (dense, body coordinates, unwrapped heading) as driven curves.

    Args:
        space: the car space it was planned in (turning radius, rear axle offset).
        q: (n, 3) samples of one gear segment.
        window: metres the curvature is averaged over; 0: the exact curves, one Drive per
            stretch of constant curvature.

    Returns:
        The Drives, one after another from q[0] to q[-1]; empty when q does not move.
        A window whose correction fails (or would turn tighter than the radius) falls back to
        the exact curves.
    """
    lengths, kappa, gear = segment_steps(space, q)
    if not len(lengths):
        return []
    ref = space.reference(q)
    start, end = ref[0], ref[-1]
    bounds = np.concatenate([[0.0], np.cumsum(lengths)])
    if window > 0.0 and np.ptp(kappa) > 1e-9:
        drive = _smoothed(space, start, end, bounds, kappa, gear, window)
        if drive is not None:
            return [drive]
    # exact: one Drive per run of equal curvature, each starting on the planned pose of its first sample
    jumps = np.flatnonzero(np.abs(np.diff(kappa)) > 1e-9) + 1
    out = []
    for a, b in zip([0, *jumps], [*jumps, len(kappa)]):
        nodes = _nodes(bounds[b] - bounds[a])
        out.append(_integrated(ref[a], nodes, np.full(len(nodes), kappa[a]), gear, -space.offset))
    return out


def _nodes(length: float) -> np.ndarray:
    return np.linspace(0.0, length, max(2, int(np.ceil(length / GRID)) + 1))


def _integrated(start: np.ndarray, s: np.ndarray, kappa: np.ndarray, gear: float, ahead: float) -> Drive:
    """The curve of curvature ``kappa`` (linear between the nodes ``s``) driven from the rear axle pose ``start``."""
    h = np.diff(s)
    turned = 0.5 * h * (kappa[:-1] + kappa[1:])
    theta = start[2] + np.concatenate([[0.0], np.cumsum(turned)])
    steps = _chord(gear, h, turned, theta[:-1])
    p = start[:2] + np.vstack([np.zeros((1, 2)), np.cumsum(steps, axis=0)])
    return Drive(s, kappa, theta, p, gear, ahead)


def _averaged(bounds: np.ndarray, kappa: np.ndarray, s: np.ndarray, window: float) -> np.ndarray:
    """The curvature averaged over [s - window / 2, s + window / 2] (the ends' curvature continued beyond them)."""
    turned = np.concatenate([[0.0], np.cumsum(kappa * np.diff(bounds))])
    x = np.concatenate([[bounds[0] - window], bounds, [bounds[-1] + window]])
    y = np.concatenate([[-kappa[0] * window], turned, [turned[-1] + kappa[-1] * window]])
    return (np.interp(s + 0.5 * window, x, y) - np.interp(s - 0.5 * window, x, y)) / window


def _smoothed(space: CarSpace, start, end, bounds, kappa, gear, window) -> Drive | None:
    """The averaged curve, corrected to end on ``end``; None if the correction does not converge or
    would turn tighter than the radius."""
    s = _nodes(bounds[-1])
    base = _averaged(bounds, kappa, s, window)
    # corrections go where the curve turns less than it may: (1 - |kappa| r) x (1, xi, xi^2)
    xi = 2.0 * s / s[-1] - 1.0
    room = np.clip(1.0 - np.abs(base) * space.radius, 0.0, 1.0)
    basis = np.stack([room, room * xi, room * xi**2])
    target = end.copy()
    ahead = -space.offset

    def miss(c):
        drive = _integrated(start, s, base + c @ basis, gear, ahead)
        return drive, np.array([*(drive.p[-1] - target[:2]), drive.theta[-1] - target[2]])

    c = np.zeros(3)
    drive, r = miss(c)
    for _ in range(NEWTON_STEPS):
        if np.max(np.abs(r)) <= END_TOLERANCE:
            break
        eps = 1e-7
        jac = np.column_stack([(miss(c + eps * np.eye(3)[i])[1] - r) / eps for i in range(3)])
        try:
            c = c - np.linalg.solve(jac, r)
        except np.linalg.LinAlgError:
            return None
        drive, r = miss(c)
    if np.max(np.abs(r)) > END_TOLERANCE or np.max(np.abs(drive.kappa)) * space.radius > 1.0 + 1e-9:
        return None
    return drive


def ends_on(drive: Drive, q: np.ndarray) -> bool:
    """Whether a Drive ends on the body pose q (a check for tests)."""
    return bool(np.allclose(drive.derivatives(np.array([drive.length]))[0][0], q, atol=1e-8)
                and abs(wrap_angle(drive.theta[-1] - q[2])) < 1e-8)
