"""Shortcutting a planned path over the planner's protocols (no Drake).

First a greedy pass (string pulling): from the start, a straight segment to the farthest
point of the path visible from it, points inside segments included (binary search over
arc length), then again from there. Then random shortcuts between two random waypoints
(OMPL's ``reduceVertices``), between two random points anywhere on the path (OMPL's
``shortcutPath``) and partial shortcuts that straighten one coordinate only between two
points (Geraerts and Overmars, "Creating High-quality Paths for Motion Planning", IJRR
2007), until ``patience`` attempts in a row gain nothing. Then a few sweeps of vertex
relaxation (:mod:`lazyground.motion.relax`) pull the waypoints the shortcuts left tight
between their neighbours, and optionally (``regreedy``) a second greedy pass drops the
waypoints that no longer bend around anything. The start, the goal and, when the goal sample has an approach,
the final straight approach segment are kept.

Every new segment is checked at the planner's resolution when it is tried. The fine check
(``resolution / validation_factor``, as every returned path) is deferred to the segments of
the final path that are new, because most new segments are later cut again: about 2/3 of the
greedy pass's on the Fetch scenes, most accepted shortcuts, the relaxed ones. A greedy segment
lies where the path just passes an obstacle, so now and then one fails the fine check (0.1-0.3
per Fetch path); then the whole shortening is done again with the greedy pass checking each
segment finely when it chooses it and pulling a failing one back (the first pass's fine
verdicts are kept). Only the input path's own segments, end to end,
count as checked (the planner checked them finely); a piece of one, or a run of collinear ones merged into one
segment, is checked again, because its fine check points are not the planner's and a segment grazing an obstacle
can pass at one set of points and fail at another (corpus big_box_table, seed 0: a 0.003 rad graze). When a
segment fails the fine check, the newest earlier version of the path whose segments all pass is returned, or the
input path when the failing segment goes back to the first version.
"""

from __future__ import annotations

import enum
import functools
from dataclasses import dataclass, replace

import numpy as np

from lazyground.motion.curve import segment_lengths
from lazyground.motion.edges import bisected_edge
from lazyground.motion.relax import relax
from lazyground.motion.validate import sequence_free
from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition


class ShortcutStatus(str, enum.Enum):
    SHORTENED = "shortened"
    UNCHANGED = "unchanged"  # no shortcut found (or none tried)
    DISABLED = "disabled"
    BACKTRACKED = "backtracked"  # the last version failed the fine check; an earlier, valid one is returned
    REVERTED = "reverted"  # the shortened path could not be timed (lazyground.motion.pipeline): the raw one is kept

    def __str__(self) -> str:
        return self.value


@dataclass(frozen=True)
class ShortcutSettings:
    """How hard to shorten. The random shortcuts stop at whichever comes first: ``max_iterations``
    attempts, ``time_budget`` seconds (from the start of the shortening) or ``patience`` attempts in
    a row without gain; the greedy pass before them makes a few dozen edge checks and is not cut short.
    The relaxation after them makes at most ``relax_sweeps`` sweeps, none started after the deadline;
    ``regreedy`` then pulls the string once more (not started after the deadline either)."""

    enabled: bool = True
    max_iterations: int = 100  # random shortcut attempts after the greedy pass
    time_budget: float = 1.0  # seconds
    vertex_fraction: float = 0.5  # share of attempts between two waypoints (they drop waypoints)
    partial_fraction: float = 0.2  # share of attempts that straighten one coordinate only
    greedy: bool = True  # first go straight to the farthest visible point of the path, again and again
    patience: int = 10  # stop after this many attempts in a row gain less than ``min_gain`` of the length
    # ... and a relaxation move must gain as much. 1e-2 against 1e-3, seeds 0-19 per Fetch scene (#16): motion CPU
    # -11 / -12 / -14 % (cans_1 / cans_2 / boxes_3), lengths +0.9 / +0.7 / +0.3 %, durations -2 / -3 / -6 %
    # (fewer small moves, fewer corners); 2e-2 made lengths 1.4-1.8 % longer.
    min_gain: float = 1e-2
    relax_pieces: int = 8  # relaxation first cuts segments to at most 1/relax_pieces of the length (0: no relaxation)
    relax_sweeps: int = 1  # sweeps over the waypoints (it stops earlier when a sweep moves none)
    relax_halvings: int = 1  # a blocked move is tried again at 1/2, ... 1/2**relax_halvings of its step
    regreedy: bool = False  # after shortcuts or relaxation changed the path, a second greedy pass (fewer waypoints, ~+60 % checks)

    def __post_init__(self):
        shares = (self.vertex_fraction, self.partial_fraction)
        counts = (self.max_iterations, self.relax_pieces, self.relax_sweeps, self.relax_halvings)
        if min(counts) < 0 or not self.time_budget >= 0 or min(shares) < 0 or sum(shares) > 1 or self.patience < 1:
            raise ValueError("shortcut settings: max_iterations, relax_pieces, relax_sweeps, relax_halvings >= 0, "
                             "time_budget >= 0, shares >= 0 summing to <= 1, patience >= 1")


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
    direct_length: float = float("nan")  # start to goal in a straight line: a lower bound of ``length``


@dataclass(frozen=True)
class _Path:
    """Waypoints and, per segment, whether it is new (not a piece of the input path)."""

    space: ConfigSpace
    q: list
    new: list  # per segment: 0 for a piece of the input path, else the version that made it

    @functools.cached_property
    def cum(self) -> np.ndarray:
        """Arc length at each waypoint (computed once per version; attempts reuse it)."""
        return np.concatenate([[0.0], np.cumsum(self.lengths)])

    @functools.cached_property
    def embedded(self) -> np.ndarray:
        """The waypoints in the space's embedding (their Euclidean distances are the metric's)."""
        return self.space.embed(np.array(self.q))

    @functools.cached_property
    def lengths(self) -> np.ndarray:
        return np.linalg.norm(np.diff(self.embedded, axis=0), axis=1)  # (curve.segment_lengths, embedding kept)

    def cut(self, i: int, j: int, middle: list, new_middle: list) -> "_Path":
        """Waypoints ..q[i], *middle, q[j].. ; ``new_middle`` flags the len(middle) + 1 segments between."""
        return _Path(self.space, self.q[: i + 1] + middle + self.q[j:], self.new[:i] + new_middle + self.new[j:])


def shortcut_path(
    space: ConfigSpace,
    checker: ValidityChecker,
    path: np.ndarray,
    resolution: float,
    validation_factor: float,
    settings: ShortcutSettings,
    rng: np.random.Generator,
    keep_last_segment: bool = False,
    stop: StopCondition | None = None,
) -> ShortcutResult:
    """Shorten ``path`` (start and goal kept).

    Args:
        space: the planner's configuration space (interpolation, metric).
        checker: the planner's validity checker (``edge_free``, ``configs_free``).
        path: (n, dim) waypoints, valid at ``resolution / validation_factor``.
        resolution: the planner's edge-check spacing; new segments are tried at it.
        validation_factor: new segments of the result are checked at ``resolution / validation_factor``.
        settings: budgets and the shares of the three kinds of shortcut.
        rng: the only source of randomness (the plan's generator).
        keep_last_segment: keep the last segment as it is (a goal sample's straight approach).
        stop: when the random shortcuts and the relaxation stop trying (default: ``settings.time_budget``
            seconds from now).

    Returns:
        A ShortcutResult; ``path`` is never longer than ``raw_path`` and every segment of it is
        free at the fine resolution.
    """
    if stop is None:
        stop = StopCondition.after(settings.time_budget)
    t0 = stop.now()
    raw = np.asarray(path, float)
    raw_length = space.path_length(raw)

    def done(status, out, iterations=0, accepted=0, length=None):
        length = (raw_length if out is raw else space.path_length(out)) if length is None else length
        return ShortcutResult(status, out, raw, raw_length, length, iterations, accepted,
                              stop.now() - t0, space.distance(raw[0], raw[-1]))

    if not settings.enabled:
        return done(ShortcutStatus.DISABLED, raw)
    body, tail = (raw[:-1], raw[-1:]) if keep_last_segment and len(raw) > 2 else (raw, raw[:0])
    start = _drop_redundant(space, _Path(space, list(body), [0] * (len(body) - 1)))
    fine = _FineCheck(space, checker, resolution / validation_factor, raw)
    checked = bisected_edge(space, checker, resolution)
    edge = _remembered(checked)  # a redo's greedy pass asks the same edges again
    probe = _remembered(lambda a, b: checked(a, b, "probes"))
    versions, iterations, backtracked = _shorten(space, edge, fine, start, settings, rng, stop, lazy=True, probe=probe)
    if versions is None:  # a segment of the unchecked greedy pass failed the fine check: again, checking each as chosen
        rest = replace(settings, max_iterations=settings.max_iterations - iterations)  # attempts in all stay within it
        versions, more, backtracked = _shorten(space, edge, fine, start, rest, rng, stop, lazy=False, probe=probe)
        iterations += more
    if not versions:  # a piece of the input path (version 0's) fails: the input path itself
        return done(ShortcutStatus.BACKTRACKED, raw, iterations, 0)
    out = np.array(versions[-1].q)
    out = np.vstack([out, tail]) if len(tail) else out
    length = space.path_length(out)
    if length >= raw_length:
        return done(ShortcutStatus.UNCHANGED, raw, iterations, 0)
    return done(ShortcutStatus.BACKTRACKED if backtracked else ShortcutStatus.SHORTENED, out, iterations, len(versions) - 1,
                length)


def _segment_key(a: np.ndarray, b: np.ndarray) -> tuple[bytes, bytes]:
    """The key under which a segment's check is remembered (its exact end points)."""
    return a.tobytes(), b.tobytes()


def _remembered(edge):
    """``edge`` with its answers kept per (a, b)."""
    known = {}

    def remembered(a: np.ndarray, b: np.ndarray, *part) -> bool:
        key = _segment_key(a, b)
        if key not in known:
            known[key] = edge(a, b, *part)
        return known[key]

    return remembered


def _shorten(space: ConfigSpace, edge, fine: "_FineCheck", start: _Path, settings: ShortcutSettings,
             rng: np.random.Generator, stop: StopCondition, lazy: bool, probe=None) -> tuple[list | None, int, bool]:
    """Greedy pass, random shortcuts, relaxation, then the fine check of the result, going back to the newest
    version whose segments all pass. Returns (versions, attempts, whether it went back); versions is [] when
    a piece of the input path fails.

    ``lazy``: the greedy pass checks its segments at the planner's resolution only; their fine check comes with
    the final path's (about 2/3 of them are cut again by the shortcuts and the relaxation). Its path is version 1
    (the input's is 0, dropped from what is returned), and versions is None when one of its segments fails: the
    caller then shortens again with ``lazy`` False, where the greedy pass checks each segment finely when it
    chooses it and pulls a failing one back.
    """
    versions = [start]
    lazy = lazy and settings.greedy and len(start.q) > 2
    if lazy:
        versions.append(_drop_redundant(space, _greedy(space, edge, None, start, born=1, probe=probe)))
    elif settings.greedy and len(start.q) > 2:
        versions[0] = _drop_redundant(space, _greedy(space, edge, fine.segment_free, start, probe=probe))
    iterations = _random_shortcuts(space, edge, versions, settings, rng, stop)
    _relax(space, edge, versions, settings, stop)
    if settings.regreedy and len(versions) > 1 + lazy and len(versions[-1].q) > 2 and not stop.should_stop():
        versions.append(_drop_redundant(space, _greedy(space, edge, fine.segment_free, versions[-1], probe=probe)))
    backtracked = False
    while (bad := fine.first_failure(versions[-1])) is not None:
        if lazy and bad == 1:
            return None, iterations, True
        del versions[bad:]  # back to the newest version made before the failing segment
        backtracked = True
        if not versions:
            break
    return versions[1:] if lazy and versions else versions, iterations, backtracked


def _random_shortcuts(space: ConfigSpace, edge, versions: list, settings: ShortcutSettings, rng: np.random.Generator,
                      stop: StopCondition) -> int:
    """Random shortcuts until ``settings.max_iterations`` attempts, the stop condition or ``patience`` attempts
    in a row without gain; every shorter path is appended to ``versions``. Returns the attempts."""
    work = versions[-1]
    iterations = idle = 0
    while (iterations < settings.max_iterations and idle < settings.patience and not stop.should_stop()
           and len(work.q) > 2):
        iterations += 1
        idle += 1
        draw = rng.random()
        born = len(versions)
        # an attempt that cannot gain ``min_gain`` of the length is dropped before its check
        gain = settings.min_gain * work.cum[-1]
        if draw < settings.vertex_fraction:
            new = _try_vertices(edge, work, rng, born, gain)
        elif draw < settings.vertex_fraction + settings.partial_fraction:
            new = _try_partial(space, edge, work, rng, born, gain)
        else:
            new = _try_full(space, edge, work, rng, born, gain)
        if new is not None:
            if work.cum[-1] - new.cum[-1] >= settings.min_gain * work.cum[-1]:
                idle = 0
            work = _drop_redundant(space, new)
            versions.append(work)
    return iterations


def _relax(space: ConfigSpace, edge, versions: list, settings: ShortcutSettings, stop: StopCondition) -> None:
    """Relaxation sweeps over the newest version (lazyground.motion.relax); each sweep that moves a waypoint
    appends a version, so a segment failing the fine check costs only the sweeps from its own on."""
    work = versions[-1]
    if not settings.relax_pieces or len(work.q) < 3:
        return
    sweeps = relax(space, edge, work.q, work.new, len(versions), settings.relax_pieces, settings.relax_sweeps,
                   settings.relax_halvings, settings.min_gain * work.cum[-1], lambda: not stop.should_stop())
    versions.extend(_drop_redundant(space, _Path(space, q, new)) for q, new in sweeps)


class _FineCheck:
    """The fine check of a version's segments, each distinct segment checked once; the input path's own
    segments (``raw``, checked finely by the planner) count as passed."""

    def __init__(self, space: ConfigSpace, checker: ValidityChecker, resolution: float, raw: np.ndarray):
        self.space, self.checker, self.resolution = space, checker, resolution
        self.known = {_segment_key(a, b): True for a, b in zip(raw[:-1], raw[1:])}

    def first_failure(self, p: _Path) -> int | None:
        """The version that made the first segment failing the check (0: a piece of the input path), or None
        if all pass.

        The segments are checked in path order up to the first that fails: the ones after it may never be
        needed (the version goes), and when they are (an earlier version keeps them) they are checked then.
        """
        for a, b, born in zip(p.q[:-1], p.q[1:], p.new):
            if not self.segment_free(a, b):
                return born
        return None

    def segment_free(self, a: np.ndarray, b: np.ndarray) -> bool:
        """Whether a -> b passes the check (remembered)."""
        key = _segment_key(a, b)
        if key not in self.known:
            self.known[key] = bool(np.all(sequence_free(self.checker, self.space.discretize(a, b, self.resolution))))
        return self.known[key]

    @property
    def failed(self) -> set:
        """The segments (keys) that failed."""
        return {key for key, ok in self.known.items() if not ok}


# The search for the farthest visible point halves its interval until it is 1/2**GREEDY_SPLITS of the whole
# path's length (not of the rest of the path: later segments, with less path left, need fewer edge checks
# for the same precision). Against 6 halvings of the rest of the path, seeds 0-19 per Fetch scene (#16): motion
# CPU -3 % / -1 % / -7 % on cans_1 / cans_2 / boxes_3, lengths and durations within 1.3 %.
GREEDY_SPLITS = 6
GREEDY_BACKOFFS = 3  # pull-backs of a farthest point whose segment fails the fine check


def _greedy(space: ConfigSpace, edge, fine_free, path: _Path, born: int = 0, probe=None) -> _Path:
    """String pulling: from the start, a straight segment to the farthest point of the path visible
    from it, then again from there.

    The farthest point is found by binary search over arc length (points inside segments
    included) with ``edge``, the planner's check; given ``probe`` (``edge``'s probes only), the search
    asks the probes and only the point it settles on is checked in full. It lies where the segment just passes an
    obstacle, so it is then checked at the fine resolution (``fine_free``) and, failing that,
    pulled back towards the current point. Every segment it makes is therefore checked at the
    fine resolution (flag 0: none backtracks past it); the pieces of the input's segments it
    follows keep their flags (all 0 on the first pass, over the planner's path). With ``fine_free``
    None its segments are not checked finely here and are flagged ``born``.
    """
    if fine_free is None:
        fine_free = lambda a, b: True  # noqa: E731  (checked later, with the final path's new segments)
    else:
        born = 0
    q, cum = path.q, path.cum
    out, flags = [q[0]], []
    cur, k = q[0], 0  # the current point lies on segment k (q[k] -> q[k + 1])
    while k < len(q) - 2:
        if edge(cur, q[-1]) and fine_free(cur, q[-1]):
            out.append(q[-1])
            return _Path(space, out, flags + [born])
        # q[k + 1] is visible (along the segment), the goal is not. The search asks only the edges' probes and
        # checks the rest of the edge it settles on; a wall the fine check finds between the coarse checks redoes
        # the search with full checks (then the pull-backs below)
        lo = _farthest(space, q, cum, cur, k, probe or edge, (lambda a, b: edge(a, b, "rest")) if probe else None)
        if probe and lo > cum[k + 1] and not fine_free(cur, _point_at(space, q, cum, lo)[1]):
            lo = _farthest(space, q, cum, cur, k, edge)
        for _ in range(GREEDY_BACKOFFS):
            if lo <= cum[k + 1] or fine_free(cur, _point_at(space, q, cum, lo)[1]):
                break
            lo = cum[k + 1] + 0.5 * (lo - cum[k + 1])
            if not edge(cur, _point_at(space, q, cum, lo)[1]):
                lo = cum[k + 1]
        else:
            lo = cum[k + 1]
        if lo <= cum[k + 1]:  # only the next waypoint: follow the segment to it
            flags.append(path.new[k])
            cur, k = q[k + 1], k + 1
        else:
            flags.append(born)
            k, cur = _point_at(space, q, cum, lo)
        out.append(cur)
    out.append(q[-1])  # the rest of the last segment
    return _Path(space, out, flags + [path.new[-1]])


def _farthest(space: ConfigSpace, q: list, cum: np.ndarray, cur: np.ndarray, k: int, edge, rest=None) -> float:
    """The arc length of the farthest point of the path after q[k + 1] that ``edge`` says ``cur`` sees (binary search).

    With ``rest`` (the check of the rest of an edge whose ``edge`` answer, its probes, passed), the point the
    search settles on must pass it too; a point that fails bounds the search, which goes on from the point
    before it (every point it passes through saw its probes pass).
    """
    seen, hi = [cum[k + 1]], cum[-1]
    while True:
        while hi - seen[-1] > cum[-1] / 2**GREEDY_SPLITS:
            mid = 0.5 * (seen[-1] + hi)
            if edge(cur, _point_at(space, q, cum, mid)[1]):
                seen.append(mid)
            else:
                hi = mid
        if rest is None or len(seen) == 1 or rest(cur, _point_at(space, q, cum, seen[-1])[1]):
            return seen[-1]
        hi = seen.pop()


def _try_vertices(edge, path: _Path, rng, born: int, min_gain: float) -> _Path | None:
    """Replace the waypoints between two random waypoints i < j - 1 by one straight segment (if it gains ``min_gain``)."""
    i, j = np.sort(rng.choice(len(path.q), 2, replace=False))
    if j - i < 2 or path.cum[j] - path.cum[i] - path.space.distance(path.q[i], path.q[j]) < min_gain:
        return None
    if not edge(path.q[i], path.q[j]):
        return None
    return path.cut(i, j, [], [born])


def _point_at(space: ConfigSpace, q: list, cum: np.ndarray, s: float) -> tuple[int, np.ndarray]:
    """The segment index k (q[k] -> q[k + 1]) holding arc length s, and the point there."""
    # plain min/max on Python floats: np.clip on scalars cost ~2/3 of this function (it runs ~50-90 times a path)
    k = min(max(int(cum.searchsorted(s, side="right")) - 1, 0), len(q) - 2)
    lo, hi = float(cum[k]), float(cum[k + 1])
    t = 0.0 if hi - lo <= 0 else (float(s) - lo) / (hi - lo)
    return k, space.interpolate(q[k], q[k + 1], min(max(t, 0.0), 1.0))


def _two_points(space: ConfigSpace, path: _Path, rng: np.random.Generator):
    """Two random points on different segments, in path order: (ka, a, kb, b, cum), or None."""
    cum = path.cum
    if cum[-1] <= 0:
        return None
    sa, sb = np.sort(rng.random(2) * cum[-1])
    ka, a = _point_at(space, path.q, cum, sa)
    kb, b = _point_at(space, path.q, cum, sb)
    return None if ka == kb else (ka, a, kb, b, cum)


def _try_full(space, edge, path: _Path, rng, born: int, min_gain: float) -> _Path | None:
    """Replace the stretch between two random points by one straight segment, if free and ``min_gain`` shorter."""
    picked = _two_points(space, path, rng)
    if picked is None:
        return None
    ka, a, kb, b, cum = picked
    q = path.q
    old = space.distance(a, q[ka + 1]) + (cum[kb] - cum[ka + 1]) + space.distance(q[kb], b)
    if space.distance(a, b) > old - min_gain or not edge(a, b):
        return None
    # q[ka] -> a and b -> q[kb + 1] are pieces of old segments: as new as those were
    return path.cut(ka, kb + 1, [a, b], [path.new[ka], born, path.new[kb]])


def _try_partial(space, edge, path: _Path, rng, born: int, min_gain: float) -> _Path | None:
    """Straighten one coordinate between two random points (the others follow the path), if free and ``min_gain`` shorter."""
    picked = _two_points(space, path, rng)
    if picked is None:
        return None
    ka, a, kb, b, cum = picked
    j = int(rng.integers(space.dim))
    old = [a] + path.q[ka + 1 : kb + 1] + [b]
    along = np.concatenate([[0.0], np.cumsum(segment_lengths(space, np.array(old)))])
    if along[-1] <= 0:
        return None
    diff_j = space.difference(a, b)[j]
    new = np.array(old)
    new[:, j] = a[j] + along / along[-1] * diff_j
    if space.wrap[j]:
        new = space.interpolate(new, new, 0.0)  # interpolate wraps angles
    if space.path_length(new) > along[-1] - min_gain:
        return None
    if not all(edge(p, q) for p, q in zip(new[:-1], new[1:])):
        return None
    middle = list(new)
    return path.cut(ka, kb + 1, middle, [path.new[ka]] + [born] * (len(middle) - 1) + [path.new[kb]])


def _drop_redundant(space: ConfigSpace, path: _Path) -> _Path:
    """Drop repeated waypoints and waypoints on the straight segment between their neighbours.

    A run of interior waypoints each on the segment between its neighbours lies on one
    segment from the run's first neighbour to its last, so the whole run goes at once.
    (Wrapping coordinates' chords are not additive: such waypoints stay, which is safe.)
    """
    d = path.lengths
    if np.any(d <= 1e-12):  # repeated waypoints (rare): keep the first of each run, and the goal itself
        q, new = np.array(path.q), np.array(path.new)
        idx = [0]
        for k in range(1, len(q)):
            if space.distance(q[idx[-1]], q[k]) > 1e-12:
                idx.append(k)
            elif k == len(q) - 1:
                idx[-1:] = [k] if len(idx) > 1 else [0, k]
        return _drop_redundant(space, _Path(space, list(q[idx]), list(np.maximum.reduceat(new, idx[:-1]))))
    if len(path.q) < 3:
        return path
    e = path.embedded
    skip = np.linalg.norm(e[2:] - e[:-2], axis=1)  # q[k] -> q[k + 2]
    on_line = np.abs(d[:-1] + d[1:] - skip) <= 1e-9 * np.maximum(1.0, skip)
    if not on_line.any():
        return path
    keep = np.concatenate([[True], ~on_line, [True]])
    starts = np.flatnonzero(keep)[:-1]
    born = np.maximum.reduceat(np.array(path.new), starts)  # a merged segment is as new as its newest piece
    return _Path(space, list(np.array(path.q)[keep]), list(born))
