"""Reward-penalty that covers the goal regions as the search rejects them (issue #33).

With many interpretations and few reachable, the paper's rule draws more goal samples only
when the *selected* sample is stuck, then resets every weight to 0.5 and rebuilds the heap
(O(N) per resampling); the two-tree planner waits until *every* sample is stuck (a scan over
all of them per penalty). Both leave most regions without a sample for a long time: the goal
source hands samples out region by region, so the reachable region's turn comes after about
N / resample_count resamplings.

:class:`Cover` keeps the reward-penalty weights but (1) asks for more samples whenever a sample it
penalises falls below the threshold, whatever the others' weights (a region whose goal tree
stays blocked makes room for the next regions at once), half as many as it holds, so that the
regions are covered after O(log N) stuck samples while the goal-sampling work stays within a
constant factor of what the search has rejected so far, and (2) never resets the old
weights: a new sample enters at weight 1 on a lazily updated max-heap, so select, reward and
penalty cost O(log N), not O(N). (3) It asks the search for one goal sample per iteration until
there are as many samples as goal regions (the goal source hands them out region by region):
coverage paced by the search, one draw (at most ``attempts_per_sample`` attempts) per
iteration, instead of all regions up front (eager) or one region per resampling round.
(4) Goal sampling is rationed against the search: coverage draws and the draws a stuck sample asks
for wait while the goal source's attempts exceed ``free_attempts`` plus ``attempts_per_iteration``
per iteration (counted, not timed: a seed gives the same run anywhere). On arm racks an IK attempt
costs about two iterations and 1-7 % of them are valid; unpaced, each iteration spent up to a whole
draw (10 attempts) on cans that never yield, and IK was ~90 % of the time at N = 64.
(5) With IK goals (a source with ``hopeless_reasons``) it chooses which region each attempt goes to
(:meth:`Cover.region_chooser`, :mod:`lazyground.planning.region_bandit`), and only iterations in which no goal
tree progresses earn its budget, at 0.25 attempts an iteration plus 50 free (:meth:`Cover.ik_allowance`): a goal
sample whose last credited step brought its tree closer to the start tree holds goal sampling until a step of it
is penalised. On the Fetch rack the reachable can's sample often comes first and its tree then connects alone,
while 1 attempt an iteration went on (layout 6: 300 IK attempts for round-robin's run, 5,673 for cover's).
(6) In the two-tree planner, while no goal tree can grow (every sample's tree still its root after ``blocked_after``
collided steps, :mod:`lazyground.planning.blocked`, or no sample yet) the budget earns 1 attempt an iteration: the
iterations between IK attempts were the N = 64 racks' growth (Panda, 10 layouts: 76,363 -> 25,240 iterations).
(7) A sample whose tree has taken ``age_after`` steps without the search ending ages (not live; its region may get
another sample): a grasp whose tree grows but never meets the start tree (Fetch 64 layout 14: 60,722 -> 4,434 iterations).
"""

from __future__ import annotations

import heapq

import numpy as np

from lazyground.planning.region_bandit import StagedBandit
from lazyground.planning.weights import StrategySettings, penalty_weight, reward_weight


class Cover:
    """Reward-penalty weights on a lazy max-heap; a stuck sample asks for one more sample at once."""

    covers_regions = True  # the search draws one more sample per iteration until samples outnumber regions
    resample_alone = True  # a stuck sample asks for samples even while other samples progress
    growth = 0.5  # each request draws this fraction of the samples held: their number grows geometrically
    attempts_per_iteration = 1.0  # coverage draws pause while goal-sampling attempts exceed this per iteration
    free_attempts = 200  # ... plus this many (a few regions are covered at once, as before the pacing)
    # With a source that tells hopeless attempts apart (IK), this strategy chooses its regions (region_chooser), and
    # its budget is this per iteration in which no goal tree progresses, plus these free: an IK attempt costs 2-3
    # iterations on the Fetch rack, so 1 per iteration put 70-75 % of a long run's time in IK.
    ik_attempts_per_iteration = 0.25
    ik_free_attempts = 50
    # ... and this per iteration while no goal tree can grow: every sample's tree is its root after ``blocked_after``
    # collided steps from it (lazyground.planning.blocked: a can behind a window), or there is no sample yet
    ik_blocked_attempts_per_iteration = 1.0
    blocked_after = 10
    # ... or every live sample's tree has had this many steps without meeting the start tree (aged: its region may get
    # another sample; lazyground.planning.blocked)
    age_after = 1500

    def __init__(self, settings: StrategySettings = StrategySettings()):
        self._threshold = settings.resample_threshold
        self._w: dict[int, float] = {}
        self._heap: list[tuple[float, int]] = []  # (-weight, index); stale entries skipped
        self._ik = False  # whether this strategy chooses the regions (region_chooser): the IK budget then
        self._progress: set[int] = set()  # samples whose last credited step was progress (rewarded)
        self._earned = 0.0  # IK attempts earned by the iterations seen so far (ik_allowance)
        self._seen = 0  # the iteration count at the last ik_allowance call

    @property
    def batch(self) -> int:
        """Samples drawn per request: half as many as held (at least one)."""
        return max(1, int(self.growth * len(self._w)))

    def add(self, indices: list[int]) -> None:
        for i in indices:
            self._w[i] = 1.0
            heapq.heappush(self._heap, (-1.0, i))

    def select(self, rng: np.random.Generator) -> int:
        while -self._heap[0][0] != self._w[self._heap[0][1]]:
            heapq.heappop(self._heap)
        return self._heap[0][1]

    def weight(self, index: int) -> float:
        return self._w[index]

    def _set(self, index: int, w: float) -> None:
        if w != self._w[index]:
            self._w[index] = w
            heapq.heappush(self._heap, (-w, index))

    def reward(self, index: int) -> None:
        self._progress.add(index)
        self._set(index, reward_weight(self._w[index]) if self._w[index] < 1.0 else 1.0)

    def penalize(self, index: int) -> bool:
        self._progress.discard(index)
        w = penalty_weight(self._w[index])
        self._set(index, w)
        return w < self._threshold


    def region_chooser(self, goals) -> StagedBandit | None:
        """The order ``goals`` should try its regions in (the search hands it to the source), or None for its own:
        a :class:`StagedBandit` where the source tells hopeless attempts apart (IK: out of reach); a parking source's
        attempt is one collision check, and it keeps its round robin and this strategy its plain budget."""
        reasons = getattr(goals, "hopeless_reasons", ())
        if not reasons:
            return None
        self._ik = True
        deferred = getattr(goals, "blocked_approaches", None)  # regions whose hand cannot back out: tried later
        return StagedBandit(goals.stats, reasons, deferred() if callable(deferred) else ())

    def ik_allowance(self, iterations: int, growing: bool = True) -> float:
        """Goal-sampling attempts allowed by now: ``free_attempts`` plus ``attempts_per_iteration`` per search
        iteration; with a chosen order (IK), ``ik_free_attempts`` plus ``ik_attempts_per_iteration`` per iteration
        in which no sample progressed, ``ik_blocked_attempts_per_iteration`` per iteration in which no goal tree can
        grow (``growing`` False: the search's :class:`lazyground.planning.blocked.BlockedTrees`). The state at a
        call counts for the iterations since the last one."""
        if not self._ik:
            return self.free_attempts + self.attempts_per_iteration * iterations
        if not growing:
            self._earned += self.ik_blocked_attempts_per_iteration * (iterations - self._seen)
        elif not self._progress:
            self._earned += self.ik_attempts_per_iteration * (iterations - self._seen)
        self._seen = iterations
        return self.ik_free_attempts + self._earned


class CoverConnect(Cover):
    """:class:`Cover`, and each new start-tree node is also a target for the strategy's goal tree
    (the bidirectional planner's ``_connect_selected``)."""

    connects_selected = True
