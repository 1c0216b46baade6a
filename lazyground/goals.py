"""Goal sources: lazily turn goal regions into valid goal configurations.

:class:`RoundRobinGoalSource` owns the bookkeeping shared by every sampler
(round-robin over regions, per-region statistics, giving up on a region that
never yields a valid sample); subclasses say how one attempt on one region
goes. :class:`ConfigGoalSource` covers C-space regions (parking); the Drake IK
sampler for workspace and placement regions lives in :mod:`lazyground.drake.ik`.

Which source samples which region kind is a registry, as OMPL's
``GoalSampleableRegion`` family: :func:`register_goal_source` maps a kind to a
factory ``(regions, world) -> source``; :func:`goal_source_for` looks it up.
The config source registers here; the IK source when :mod:`lazyground.drake`
is imported (any ``DrakeWorld`` has imported it).
"""

from __future__ import annotations

import bisect
from typing import Callable, Iterator

import numpy as np

from lazyground.planning.problem import GoalSample, RegionStats, ValidityChecker
from lazyground.planning.space import ConfigSpace
from lazyground.planning.stop import StopCondition
from lazyground.regions import REGION_KINDS, ConfigRegion, GoalRegion
from lazyground.settings import GoalSamplingSettings


REACHED_FACTOR = 4  # a region whose goals are reached but collide gets this many times the attempts
# A region none of whose goals were reached, HOPELESS_SHARE of its first HOPELESS_AFTER or more attempts failing for
# a hopeless reason (an IK target beyond the arm's reach), is given up then (issue #33: cans behind a rack's inner
# ring, 86-95 % out of reach, took 50 attempts each; the reachable can's regions fail so 35-40 % of the time).
HOPELESS_AFTER, HOPELESS_SHARE = 20, 0.9
# A region without a valid sample none of whose DEFER_AFTER or more targets got past the screen before any solve (out
# of reach, the hand alone in collision) takes one round-robin turn in DEFER, every turn again once one passes; it is
# never given up for it (issue #33: on a 64-can Panda rack 123 of the 184 regions behind the reachable ring pass under
# 2 %, the reachable can's productive grasp ~30 %; simulated over 100 seeds from measured outcome rates, the IK
# attempts to its first sample: median 3,211 -> 2,847, upper quartile 5,741 -> 3,966; N = 4 unchanged).
DEFER_AFTER, DEFER = 10, 8


class RoundRobinGoalSource:
    """Draw goal samples region by region, so every grounding gets a chance.

    A region that has had ``give_up_after`` attempts without one valid sample
    is exhausted and skipped from then on; one whose attempts failed for a reason in
    ``reached_reasons`` (the goal was reached, the configuration collided: other goals
    of the region may be free) keeps going for ``REACHED_FACTOR`` times as many
    (issue 34: a can in an open box was given up on with grasps that exist); one whose
    attempts nearly all failed for a reason in ``hopeless_reasons`` stops sooner (:meth:`region_budget`).
    """

    reached_reasons: tuple[str, ...] = ()
    hopeless_reasons: tuple[str, ...] = ()  # failures that say the region's goals lie where the robot never gets
    screened_reasons: tuple[str, ...] = ()  # failures before any solve: a region failing nearly only so is deferred

    def __init__(self, regions: tuple[GoalRegion, ...], give_up_after: int | None = None,
                 attempts_per_sample: int | None = None, sampling: GoalSamplingSettings | None = None,
                 unreachable: dict[int, str] | None = None):
        """Args:
            regions: the goal regions.
            give_up_after, attempts_per_sample: override ``sampling``'s (for tools and tests).
            sampling: the run's goal-sampling settings (default: their declared defaults).
            unreachable: regions proven unreachable (index -> by what): never sampled, given up from the start.
        """
        sampling = GoalSamplingSettings() if sampling is None else sampling
        self.regions = tuple(regions)
        self.stats = [RegionStats() for _ in self.regions]
        for j, why in (unreachable or {}).items():
            self.stats[j].unreachable = why
        self._give_up_after = sampling.give_up_after if give_up_after is None else give_up_after
        self.attempts_per_sample = sampling.attempts_per_sample if attempts_per_sample is None else attempts_per_sample
        self.next_region = 0
        self._time = 0.0
        # kept as attempts are made, so that no draw scans every region (issue #33: hundreds of regions)
        self.total_attempts = self.total_valid = 0
        self._open = sorted(j for j in range(len(self.regions)) if not self.region_exhausted(j))  # not given up yet
        # the strategy's choice of regions (the search sets it: lazyground.planning.region_bandit); None: round robin
        self.chooser = None
        self._schedule: list[int] = []  # with a chooser: the region of each attempt counter, blocks appended as needed
        self._block: tuple = (None, [])  # ((chooser, its version, open regions) it was made at, the chooser's last block)

    def seed_near(self) -> bool:
        """Solve goals from the step's start from now on (the branch nearest it); False: this source cannot."""
        return False

    @property
    def sample_time(self) -> float:
        return self._time

    def region_budget(self, j: int) -> int:
        """Attempts region ``j`` may take without a valid sample before it is given up: fewer when nearly all
        of at least HOPELESS_AFTER attempts failed for a ``hopeless_reasons`` reason (issue #33)."""
        st = self.stats[j]
        if any(st.failures.get(r, 0) for r in self.reached_reasons):
            return self._give_up_after * REACHED_FACTOR
        if self.hopeless_reasons and st.attempts >= HOPELESS_AFTER:
            if sum(st.failures.get(r, 0) for r in self.hopeless_reasons) >= HOPELESS_SHARE * st.attempts:
                return min(st.attempts, self._give_up_after)
        return self._give_up_after

    def deferred(self, j: int) -> bool:
        """Whether region ``j`` takes one round-robin turn in DEFER: no valid sample, and none of its DEFER_AFTER or
        more attempts got past the screen (every one failed for a ``screened_reasons`` reason)."""
        st = self.stats[j]
        if not self.screened_reasons or st.valid or st.attempts < DEFER_AFTER:
            return False
        return sum(st.failures.get(r, 0) for r in self.screened_reasons) >= st.attempts

    def region_exhausted(self, j: int) -> bool:
        st = self.stats[j]
        return bool(st.unreachable) or (st.valid == 0 and st.attempts >= self.region_budget(j))

    def exhausted(self) -> bool:
        return not self._open

    def _record(self, j: int, sample: GoalSample | None, reason: str, seconds: float) -> None:
        """Count one attempt on region j; a region it gives up leaves the open list."""
        st = self.stats[j]
        st.attempts += 1
        st.time += seconds
        self.total_attempts += 1
        if sample is None:
            st.fail(reason)
            if self.region_exhausted(j):
                k = bisect.bisect_left(self._open, j)
                if k < len(self._open) and self._open[k] == j:
                    del self._open[k]
        else:
            st.valid += 1
            self.total_valid += 1
        if self.chooser is not None:
            self.chooser.observe(j, sample is not None, reason in self.hopeless_reasons)

    def draw(self, n: int, rng: np.random.Generator, stop: StopCondition) -> list[GoalSample]:
        """Up to n new valid samples, round-robin over the regions; fewer if attempts run out or ``stop``
        says so (its deadline or interrupt: the iteration cap is the planner's)."""
        out: list[GoalSample] = []
        budget = n * self.attempts_per_sample
        t0 = stop.now()
        try:
            while len(out) < n and budget > 0 and not self.exhausted() and not stop.should_stop():
                plan = self.plan(self.next_region, min(budget, self.batch_size(n - len(out))))
                results = self.attempts(plan, rng, stop)
                try:
                    for index, (j, after) in enumerate(plan):  # the attempts in round-robin order, as if made one by one
                        if len(out) >= n or budget <= 0 or stop.should_stop():
                            break
                        if index and self.region_exhausted(j):  # given up since the plan was made (the early
                            break  # give-up rule): plan afresh from here, as the batch's queue would
                        sample, reason, seconds = next(results)
                        self.next_region = after
                        budget -= 1
                        self._record(j, sample, reason, seconds)
                        if sample is not None:
                            out.append(sample)
                finally:
                    results.close()
        finally:
            self._time += stop.now() - t0
        return out

    def plan(self, position: int, k: int) -> list[tuple[int, int]]:
        """The next ``k`` attempts in round-robin order from counter ``position``: (region, counter after it).

        Exhausted regions are skipped, and a region without a valid sample gets no
        more planned attempts than it has left before it is given up (as if each
        planned attempt failed). Fewer than ``k`` when no region can take one.
        """
        if self.chooser is not None:
            return self._chosen(position, k)
        m, open_ = len(self.regions), self._open
        left: dict[int, int] = {}  # attempts each visited region has left (only those visited: no scan)
        out: list[tuple[int, int]] = []
        idle = 0  # open regions passed in a row without a planned attempt
        while len(out) < k and open_ and idle < DEFER * len(open_):
            # the next open region at or after the counter (given-up regions are passed over, as before)
            i = bisect.bisect_left(open_, position % m)
            j = open_[i] if i < len(open_) else open_[0]
            position += (j - position % m) % m + 1
            if (position // m + j) % DEFER and self.deferred(j):  # a deferred region's turn in DEFER (staggered)
                idle += 1
                continue
            if self._take(j, k, left):
                out.append((j, position))
                idle = 0
            else:
                idle += 1
        return out

    def _take(self, j: int, k: int, left: dict[int, int]) -> bool:
        """Whether region j takes one more of the ``k`` planned attempts: ``left`` holds the attempts each region
        visited so far has left (set at its first visit: its budget less its attempts until it has a valid sample)."""
        if j not in left:
            st = self.stats[j]
            left[j] = self.region_budget(j) - st.attempts if st.valid == 0 else k
        left[j] -= 1
        return left[j] >= 0

    def _chosen(self, position: int, k: int) -> list[tuple[int, int]]:
        """:meth:`plan` in the chooser's order: counter ``position`` is the schedule's entry ``position``; the schedule
        grows by the chooser's blocks as the counters pass its end (so a plan made again from a counter is the same,
        as the batch solver's look-ahead needs). Exhausted regions and those out of attempts are passed over; a plan
        that has passed only entries scheduled before it (their regions spent since) goes on to the chooser's next
        block: it stopped there empty before, and the draw asked it again until its deadline (#33)."""
        out: list[tuple[int, int]] = []
        left: dict[int, int] = {}
        idle = 0  # entries passed over in a row
        asked = False  # whether this plan appended a block
        while len(out) < k and self._open and (idle <= len(self.regions) or not (out or asked)):
            while position >= len(self._schedule):
                if not asked and idle > len(self.regions):
                    idle = 0  # only entries scheduled before passed: the next block's open regions each take one
                asked = True
                self._schedule += self._next_block()
            j = self._schedule[position]
            position += 1
            if j not in left and self.region_exhausted(j):
                left[j] = 0
            if self._take(j, k, left):
                out.append((j, position))
                idle = 0
            else:
                idle += 1
        return out

    def _next_block(self) -> list[int]:
        """The chooser's next block of regions, asked again only when the chooser, its counts (``version``) or the
        open regions changed since the last: a plan that passes over many entries appends one block many times
        (#33: ~300 sorts of the open regions a request on a 64-can Fetch rack, 1 distinct)."""
        key = (self.chooser, getattr(self.chooser, "version", None), len(self._open))  # (the open list only shrinks)
        if key[1] is None or key != self._block[0]:
            self._block = (key, self.chooser.block(self._open))
        return self._block[1]

    def batch_size(self, wanted: int) -> int:
        """How many attempts to plan at once when ``wanted`` samples are missing (1: one at a time)."""
        return 1

    def attempts(self, plan: list[tuple[int, int]], rng: np.random.Generator,
                 stop: StopCondition) -> Iterator[tuple[GoalSample | None, str, float]]:
        """(sample or None, failure reason, seconds) for the planned attempts, in order, made lazily.

        The caller stops taking results once it has enough (closing the generator);
        the default makes each :meth:`attempt` only when its result is asked for.
        """
        for j, _ in plan:
            a0 = stop.now()
            sample, reason = self.attempt(j, rng, stop)
            yield sample, reason, stop.now() - a0

    def attempt(self, j: int, rng: np.random.Generator, stop: StopCondition) -> tuple[GoalSample | None, str]:
        """One try at a valid sample in region j: (sample, "") or (None, reason)."""
        raise NotImplementedError


class ConfigGoalSource(RoundRobinGoalSource):
    """Uniform samples from C-space box regions, kept when collision-free."""

    def __init__(self, regions, space: ConfigSpace, checker: ValidityChecker, **kwargs):
        super().__init__(regions, **kwargs)
        for r in self.regions:
            if not isinstance(r, ConfigRegion) or len(r.lower) != space.dim:
                raise ValueError(f"region {r.id} is not a {space.dim}-D configuration region")
        self._space = space
        self._checker = checker

    def attempt(self, j, rng, stop):
        q = self.regions[j].sample(rng)
        if not self._space.within_bounds(q):
            return None, "outside limits"
        if not self._checker.config_free(q):
            return None, "in collision"
        return GoalSample(q=q, region=j), ""


GOAL_SOURCES: dict[str, Callable[..., RoundRobinGoalSource]] = {}  # region kind -> factory(regions, world)


def register_goal_source(kinds: tuple[str, ...], factory: Callable[..., RoundRobinGoalSource]) -> None:
    """Make ``factory(regions, world)`` the goal source of regions of ``kinds``.

    Raises:
        ValueError: a kind is not a registered region kind.
    """
    for kind in kinds:
        if kind not in REGION_KINDS:
            raise ValueError(f"unknown goal region kind {kind!r} (known: {', '.join(REGION_KINDS)})")
        GOAL_SOURCES[kind] = factory


def goal_source_for(regions: tuple[GoalRegion, ...], world,
                    sampling: GoalSamplingSettings | None = None) -> RoundRobinGoalSource:
    """The goal source registered for these regions' kind, built over ``world``.

    Args:
        regions: the goal regions, all sampled by one source.
        world: the world to sample in (a DrakeWorld, or any object the factory accepts).
        sampling: the run's goal-sampling settings, handed to the factory as ``sampling=`` (None: its defaults).

    Raises:
        ValueError: no regions, a kind without a registered source, or kinds needing different sources.
    """
    if not regions:
        raise ValueError("no goal regions to sample")
    factories = []
    for kind in dict.fromkeys(r.kind for r in regions):
        factory = GOAL_SOURCES.get(kind)
        if factory is None:
            raise ValueError(f"no goal source registered for region kind {kind!r} (workspace and placement: import lazyground.drake)")
        if factory not in factories:
            factories.append(factory)
    if len(factories) > 1:
        raise ValueError(f"regions of kinds {', '.join(sorted({r.kind for r in regions}))} need different goal sources")
    return factories[0](tuple(regions), world) if sampling is None else factories[0](tuple(regions), world, sampling=sampling)


def _config_source(regions, world, sampling: GoalSamplingSettings | None = None) -> ConfigGoalSource:
    """The config source over ``world``, without the regions its reach prior proves unreachable (``reach_prior``)."""
    return ConfigGoalSource(regions, world.space, world, sampling=sampling, unreachable=reach_prior_drops(regions, world, sampling))


REACH_PRIOR = "reach prior"  # the reason RegionStats.unreachable gives for the regions the reach prior drops


def reach_prior_drops(regions, world, sampling: GoalSamplingSettings | None = None) -> dict[int, str]:
    """The regions ``world``'s reach prior (a car's disc, :mod:`lazyground.planning.reach_prior`) proves
    unreachable from its start, index -> REACH_PRIOR; none when ``sampling.reach_prior`` is off or the world
    has no prior for its robot (``world.reach_prior()`` None or missing)."""
    sampling = GoalSamplingSettings() if sampling is None else sampling
    build = getattr(world, "reach_prior", None)
    prior = build() if sampling.reach_prior and callable(build) else None
    if prior is None:
        return {}
    return {j: REACH_PRIOR for j, kept in enumerate(prior.keeps_all(tuple(regions))) if not kept}


register_goal_source((ConfigRegion.kind,), _config_source)
