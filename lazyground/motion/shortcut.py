"""Shortcutting a planned path over the planner's protocols (no Drake).

Random shortcuts between two points anywhere on the path (OMPL's ``shortcutPath``) and
partial shortcuts that straighten one coordinate only between two points (Geraerts and
Overmars, "Creating High-quality Paths for Motion Planning", IJRR 2007), which help where
a full shortcut is blocked but one joint still wanders. The start, the goal and, when the
goal sample has an approach, the final straight approach segment are kept. Every new
segment is checked at the planner's resolution; the result is re-checked at the fine
resolution (``resolution / validation_factor``) as every returned path is.
"""

from __future__ import annotations

import enum
import time
from dataclasses import dataclass

import numpy as np

from lazyground.planning.problem import ValidityChecker
from lazyground.planning.search import path_is_valid
from lazyground.planning.space import ConfigSpace


class ShortcutStatus(str, enum.Enum):
    SHORTENED = "shortened"
    UNCHANGED = "unchanged"  # no shortcut found (or none tried)
    DISABLED = "disabled"
    REVERTED = "reverted"  # the shortened path failed the fine re-check: the raw path is kept

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class ShortcutSettings:
    """How hard to shorten. Both budgets apply: whichever runs out first stops it."""

    enabled: bool = True
    max_iterations: int = 300  # shortcut attempts
    time_budget: float = 1.0  # seconds
    partial_fraction: float = 0.3  # share of attempts that straighten one coordinate only

    def __post_init__(self):
        if self.max_iterations < 0 or not self.time_budget >= 0 or not 0 <= self.partial_fraction <= 1:
            raise ValueError("shortcut settings: max_iterations >= 0, time_budget >= 0, 0 <= partial_fraction <= 1")


@dataclass(frozen=True)
class ShortcutResult:
    """The path after shortcutting, the raw one, and what it cost."""

    status: ShortcutStatus
    path: np.ndarray
    raw_path: np.ndarray
    raw_length: float
    length: float
    iterations: int
    accepted: int
    time_s: float


def shortcut_path(
    space: ConfigSpace,
    checker: ValidityChecker,
    path: np.ndarray,
    resolution: float,
    validation_factor: float,
    settings: ShortcutSettings,
    rng: np.random.Generator,
    keep_last_segment: bool = False,
) -> ShortcutResult:
    """Shorten ``path`` (start and goal kept).

    Args:
        space: the planner's configuration space (interpolation, metric).
        checker: the planner's validity checker (``edge_free``, ``configs_free``).
        path: (n, dim) waypoints, valid at ``resolution / validation_factor``.
        resolution: the planner's edge-check spacing; new segments are checked at it.
        validation_factor: the result is re-checked at ``resolution / validation_factor``.
        settings: budgets and the share of partial shortcuts.
        rng: the only source of randomness (the plan's generator).
        keep_last_segment: keep the last segment as it is (a goal sample's straight approach).

    Returns:
        A ShortcutResult; ``path`` is never longer than ``raw_path`` and passes the fine re-check
        (when the shortened path fails it, the raw path comes back with status REVERTED).
    """
    t0 = time.perf_counter()
    raw = np.asarray(path, float)
    raw_length = space.path_length(raw)

    def done(status, out, iterations=0, accepted=0):
        return ShortcutResult(status, out, raw, raw_length, space.path_length(out), iterations, accepted, time.perf_counter() - t0)

    if not settings.enabled:
        return done(ShortcutStatus.DISABLED, raw)
    body, tail = (raw[:-1], raw[-1:]) if keep_last_segment and len(raw) > 2 else (raw, raw[:0])
    work = _drop_redundant(space, list(body))
    deadline = t0 + settings.time_budget
    iterations = accepted = 0
    while iterations < settings.max_iterations and time.perf_counter() < deadline and len(work) > 2:
        iterations += 1
        if rng.random() < settings.partial_fraction:
            new = _try_partial(space, checker, work, resolution, rng)
        else:
            new = _try_full(space, checker, work, resolution, rng)
        if new is not None:
            work, accepted = _drop_redundant(space, new), accepted + 1
    out = np.vstack([np.array(work), tail]) if len(tail) else np.array(work)
    if space.path_length(out) > raw_length:  # a partial shortcut never lengthens, but rounding could
        out = raw
    if out is raw or accepted == 0:
        return done(ShortcutStatus.UNCHANGED, raw, iterations, 0)
    if path_is_valid(space, checker, out, resolution / validation_factor) >= 0:
        return done(ShortcutStatus.REVERTED, raw, iterations, accepted)
    return done(ShortcutStatus.SHORTENED, out, iterations, accepted)


def _cumulative(space: ConfigSpace, path: list) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum([space.distance(a, b) for a, b in zip(path[:-1], path[1:])])])


def _point_at(space: ConfigSpace, path: list, cum: np.ndarray, s: float) -> tuple[int, np.ndarray]:
    """The segment index k (path[k] -> path[k + 1]) holding arc length s, and the point there."""
    k = int(np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(path) - 2))
    span = cum[k + 1] - cum[k]
    t = 0.0 if span <= 0 else (s - cum[k]) / span
    return k, space.interpolate(path[k], path[k + 1], float(np.clip(t, 0.0, 1.0)))


def _two_points(space: ConfigSpace, path: list, rng: np.random.Generator):
    """Two random points on different segments, in path order: (ka, a, kb, b), or None."""
    cum = _cumulative(space, path)
    if cum[-1] <= 0:
        return None
    sa, sb = np.sort(rng.random(2) * cum[-1])
    ka, a = _point_at(space, path, cum, sa)
    kb, b = _point_at(space, path, cum, sb)
    if ka == kb:
        return None
    return ka, a, kb, b, cum


def _try_full(space, checker, path: list, resolution: float, rng) -> list | None:
    """Replace the stretch between two random points by one straight segment, if free and shorter."""
    picked = _two_points(space, path, rng)
    if picked is None:
        return None
    ka, a, kb, b, cum = picked
    old = space.distance(a, path[ka + 1]) + (cum[kb] - cum[ka + 1]) + space.distance(path[kb], b)
    if space.distance(a, b) >= old - 1e-12 or not checker.edge_free(a, b, resolution):
        return None
    return path[: ka + 1] + [a, b] + path[kb + 1 :]


def _try_partial(space, checker, path: list, resolution: float, rng) -> list | None:
    """Straighten one coordinate between two random points (the others follow the path), if free and shorter."""
    picked = _two_points(space, path, rng)
    if picked is None:
        return None
    ka, a, kb, b, cum = picked
    j = int(rng.integers(space.dim))
    old = [a] + path[ka + 1 : kb + 1] + [b]
    along = _cumulative(space, old)
    if along[-1] <= 0:
        return None
    u = along / along[-1]
    diff_j = space.difference(a, b)[j]
    new = [q.copy() for q in old]
    for q, t in zip(new, u):
        q[j] = a[j] + t * diff_j
    new = [space.clip(q) if not space.wrap[j] else _rewrap(space, q) for q in new]
    if space.path_length(np.array(new)) >= along[-1] - 1e-12:
        return None
    for p, q in zip(new[:-1], new[1:]):
        if not checker.edge_free(p, q, resolution):
            return None
    return path[: ka + 1] + new + path[kb + 1 :]


def _rewrap(space: ConfigSpace, q: np.ndarray) -> np.ndarray:
    return space.interpolate(q, q, 0.0)  # interpolate wraps the angles


def _drop_redundant(space: ConfigSpace, path: list) -> list:
    """Drop repeated waypoints and waypoints on the straight line between their neighbours."""
    out = [path[0]]
    for k in range(1, len(path)):
        q = path[k]
        if space.distance(out[-1], q) <= 1e-12:
            continue
        if len(out) >= 2 and k < len(path):
            a = out[-2]
            if abs(space.distance(a, out[-1]) + space.distance(out[-1], q) - space.distance(a, q)) <= 1e-9 * max(1.0, space.distance(a, q)):
                out[-1] = q  # out[-1] lies on a -> q: the straight segment a -> q covers it
                continue
        out.append(q)
    if len(out) == 1:  # start == goal
        out.append(path[-1])
    return out
