"""Which goal regions get the next goal-sampling attempts: a strategy's choice (issue #33, Deliver 4).

The goal source's own order is round robin over the open regions (:class:`lazyground.goals.RoundRobinGoalSource`):
with many interpretations and few reachable it spends most of its attempts where IK never succeeds (the Fetch rack
at N = 64: 70-75 % of the attempts before the first valid sample on cans behind the inner ring, 89 % of those beyond
the arm's reach). A strategy that sets ``chooses_regions`` has the search hand the source a :class:`StagedBandit`:
the source then asks it for the next block of regions instead (:meth:`RoundRobinGoalSource.plan`).
"""

from __future__ import annotations

import numpy as np

BLOCK = 16  # regions scheduled at once: each open region at most once per block, the best first


PRIOR = 8  # stage 2's prior weight, in attempts, at the pooled rate (empirical Bayes)
DEFER = 2 * BLOCK  # attempts a region that is not deferred gets alone (in blocks of its own) before deferred ones come


class StagedBandit:
    """Greedy on a two-stage estimate of each region's chance that an attempt yields a valid sample, regions
    without a valid sample first (the search wants one sample per region before it wants more of one).

    Stage 1, the attempt does not fail for a hopeless reason (the source's ``hopeless_reasons``: an IK target beyond
    the arm's reach): a Laplace estimate, (within reach + 1) / (attempts + 2). Stage 2, an attempt within reach is
    valid: the region's count shrunk towards the rate pooled over every region, (valid + PRIOR x pooled) / (within
    reach + PRIOR) (few attempts are valid anywhere, so a region does not pass for hopeless after a few misses). The
    score is their product. Every region is tried once (in round-robin order, as all score alike); then the regions
    within reach go first: one whose only attempt was out of reach waits until those within reach have missed about
    14 times each (twice out of reach: 24). On the Fetch rack at N = 64, 97 % of the attempts on cans behind the inner
    ring fail out of reach, 24-27 % of those on the inner ring's (layout 0, 60 per region).

    Counts are kept as attempts are recorded (:meth:`observe`, O(1)); a block costs one sort of the open regions
    (numpy), made when the source's schedule runs out, and made again only after the counts (``version``) or the
    open regions changed (:meth:`lazyground.goals.RoundRobinGoalSource._next_block`): never per search iteration.
    """

    def __init__(self, stats: list, hopeless_reasons: tuple[str, ...], deferred=()):
        """Args: the source's per-region statistics so far (RegionStats), its hopeless failure reasons, the regions
        to try after the others of their stage (e.g. whose hand cannot back out: :mod:`lazyground.drake.approach`)."""
        self.deferred = np.isin(np.arange(len(stats)), list(deferred))
        self.attempts = np.array([st.attempts for st in stats], float)
        self.passed = self.attempts - [sum(st.failures.get(r, 0) for r in hopeless_reasons) for st in stats]
        self.valid = np.array([st.valid for st in stats], float)
        self.blocked = np.zeros(len(stats))  # valid samples whose goal tree stays its root (:meth:`block_sample`)
        self.aged = np.zeros(len(stats))  # valid samples whose goal tree grew long without connecting (:meth:`age_sample`)
        self._passed, self._valid = float(self.passed.sum()), float(self.valid.sum())  # pooled
        self.version = 0  # counts the changes to the counts: a block asked again at the same version is the same

    def observe(self, j: int, valid: bool, hopeless: bool) -> None:
        """One attempt on region ``j``: whether it gave a valid sample, whether it failed for a hopeless reason."""
        self.version += 1
        self.attempts[j] += 1
        self.passed[j] += not hopeless
        self.valid[j] += valid
        self._passed += not hopeless
        self._valid += valid

    def block_sample(self, j: int, blocked: bool) -> None:
        """A valid sample of region ``j`` turned out blocked (its goal tree cannot leave its root:
        :mod:`lazyground.planning.blocked`), or grew after all (``blocked`` False). A blocked sample counts as a miss:
        its region goes back among those without a sample, at the rate of its other attempts."""
        self.version += 1
        self.blocked[j] += 1 if blocked else -1

    def age_sample(self, j: int) -> None:
        """A valid sample of region ``j`` aged (its goal tree took many steps without meeting the start tree:
        :mod:`lazyground.planning.blocked`): the region goes back among those without a usable sample, at its own
        rate (its valid samples still count: the region does yield them, and its next one is another grasp)."""
        self.version += 1
        self.aged[j] += 1

    def _usable(self, regions: np.ndarray) -> np.ndarray:
        return self.valid[regions] - self.blocked[regions] - self.aged[regions] > 0

    def scores(self, regions: np.ndarray) -> np.ndarray:
        n, s, v = self.attempts[regions], self.passed[regions], self.valid[regions] - self.blocked[regions]
        pooled = (self._valid + 1) / (self._passed + 2)
        return (s + 1) / (n + 2) * (v + PRIOR * pooled) / (s + PRIOR)

    def block(self, open_: list[int]) -> list[int]:
        """The next regions to try, best first: up to ``BLOCK`` distinct ones among ``open_``, those without a valid
        sample that is not blocked first, deferred ones after the others of their stage, and only those others while
        one of them has had fewer than ``DEFER`` attempts (ties: fewer attempts, then the lower index, as round robin)."""
        regions = np.asarray(open_, int)
        usable = self._usable(regions)
        first = ~usable & ~self.deferred[regions] & (self.attempts[regions] < DEFER)
        if first.any() and self.deferred[regions].any():  # a bounded head start: DEFER attempts each
            regions, usable = regions[first], usable[first]
        keys = (regions, self.attempts[regions], -self.scores(regions), self.deferred[regions], usable)
        order = np.lexsort(keys)[:BLOCK]
        return [int(j) for j in regions[order]]
