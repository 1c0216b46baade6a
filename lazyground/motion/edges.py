"""Edge checks ordered to find collisions early (no Drake).

A shortcut's straight segment that collides mostly does so well inside it, where it leaves the
path it cuts, while its ends lie on that (checked) path. Drake's ``CheckEdgeCollisionFree`` steps
from one end to the other; here the same kind of configurations, ``resolution`` apart, are checked
by bisection (the middle first, then the middles of the halves, ...), one small batch per level,
the ends last, stopping at the first colliding level. A free edge has every configuration checked.
"""

from __future__ import annotations

import functools

import numpy as np

from lazyground.planning.problem import ValidityChecker
from lazyground.planning.space import ConfigSpace


# Configurations probed level by level (1 + 2 + 4) before the rest goes in one batch. Replaying the
# shortcut edges of 6 plans per scene (CPU time): probing all levels one by one cost ~20 % more than
# Drake's check on free edges; 7 probes then one batch found most collisions as early.
PROBES = 7


@functools.lru_cache(maxsize=512)
def bisection_levels(n: int) -> tuple[np.ndarray, ...]:
    """Indices 0 .. n-1 in batches: the middle of 1 .. n-2, the middles of both halves, ...; then 0 and n-1."""
    levels, spans = [], [(1, n - 2)] if n > 2 else []
    while spans:
        mids = [(lo + hi) // 2 for lo, hi in spans]
        levels.append(np.array(mids))
        spans = [s for lo, hi in spans for s in ((lo, (lo + hi) // 2 - 1), ((lo + hi) // 2 + 1, hi)) if s[0] <= s[1]]
    levels.append(np.array([0, n - 1]) if n > 1 else np.array([0]))
    return tuple(levels)


@functools.lru_cache(maxsize=512)
def probe_batches(n: int) -> tuple[np.ndarray, ...]:
    """The batches an edge of n configurations is checked in: bisection levels until PROBES configurations
    are probed, then all the rest in one (a free edge costs about what Drake's check does)."""
    levels = bisection_levels(n)
    sizes = np.cumsum([0] + [len(level) for level in levels])
    k = int(np.searchsorted(sizes, PROBES))  # the first k levels are the fewest that probe PROBES or more
    return levels[:k] + ((np.concatenate(levels[k:]),) if k < len(levels) else ())


def bisected_edge(space: ConfigSpace, checker: ValidityChecker, resolution: float):
    """``edge(a, b, part="all") -> bool``: a -> b free at ``resolution``, checked in bisection order with early exit.

    ``part`` "probes" checks only the probe levels (all of a short edge's configurations, about PROBES of a
    long one's): True says "probably free", for a search whose answer is then checked in full; "rest" checks
    the others, for an edge whose probes passed (together: the whole edge), the next bisection level first (a
    search settles where its edge just passes an obstacle: about half of those rests collide, on the Fetch scenes).
    """

    compiled = getattr(checker, "edge_part_free", None)
    if compiled is not None:  # the same order and parts, each in one compiled call with early exit

        def compiled_edge(a: np.ndarray, b: np.ndarray, part: str = "all") -> bool:
            first, stop = {"all": (0, None), "probes": (0, PROBES), "rest": (PROBES, None)}[part]
            return compiled(a, b, resolution, first, stop)

        return compiled_edge

    def edge(a: np.ndarray, b: np.ndarray, part: str = "all") -> bool:
        qs = space.discretize(a, b, resolution)
        batches = probe_batches(len(qs))
        if part != "all":
            probes = batches[:-1] if sum(len(batch) for batch in batches[:-1]) >= PROBES else batches
            if part == "probes":
                batches = probes
            else:
                levels = bisection_levels(len(qs))[len(probes):]
                batches = levels[:1] + ((np.concatenate(levels[1:]),) if len(levels) > 1 else ())
        return all(np.all(checker.configs_free(qs[batch])) for batch in batches)

    return edge
