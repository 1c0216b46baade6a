"""What users do instead of lazy grounding (issue #33), on the same checker, goal sampler and clock.

* ``nearest-first`` — ground, then plan: one planner call per interpretation, nearest object
  (or spot) first, each call with its own budget, as parking stacks try candidate spots in turn;
* ``multiplexer`` — one call, goal samples drawn only from the first goal region that yields
  any, as MoveIt's ``GoalSampleableRegionMux::sampleGoal`` does (moving on only when that region
  is given up);
* ``eager`` — IK for every goal region first (each region until it yields a sample or is given
  up), then one call with all those goal states and no more sampling (Tesseract; OMPL ``GoalStates``);
* ``independent`` — one planner per interpretation, all in one process, taking turns every
  :data:`TURN_CHECKS` collision checks (the paper's "independently and simultaneously").

Every method uses the planner of ``algorithm`` (rrt or bidirectional) unchanged; the first three
with the consecutive goal order (OMPL's), the goal source being what differs. Times include
grounding, goal sampling and every planner call until the first solution.
"""

from __future__ import annotations

import threading
from dataclasses import replace

import numpy as np

from lazyground.goals import goal_source_for
from lazyground.planning.problem import GoalSample, PlanStatus, RegionStats
from lazyground.planning.rrt import solve
from lazyground.planning.stop import default_clock
from lazyground.settings import Strategy

BASELINES = ("nearest-first", "multiplexer", "eager", "independent")
CALL_BUDGET = 10.0  # nearest-first: seconds per planner call (the ground-then-plan run)
TURN_CHECKS = 20  # independent planners: collision checks per turn


class FirstRegionSource:
    """Goal samples from the first goal region that yields any; the next one only once it is given up."""

    def __init__(self, regions, world, sampling=None):
        self.regions, self._world, self._sampling = tuple(regions), world, sampling
        self.stats = [RegionStats() for _ in self.regions]
        self._j, self._src, self._time = 0, None, 0.0

    @property
    def sample_time(self) -> float:
        return self._time + (self._src.sample_time if self._src is not None else 0.0)

    def _current(self):
        while self._j < len(self.regions):
            if self._src is None:
                self._src = goal_source_for((self.regions[self._j],), self._world, self._sampling)
                self.stats[self._j] = self._src.stats[0]
            if not self._src.exhausted():
                return self._src
            self._time += self._src.sample_time
            self._j, self._src = self._j + 1, None
        return None

    def exhausted(self) -> bool:
        return self._current() is None

    def draw(self, n, rng, stop) -> list[GoalSample]:
        while not stop.should_stop():
            src = self._current()
            if src is None:
                return []
            out = src.draw(n, rng, stop)
            if out:
                for s in out:
                    s.region = self._j
                return out
        return []


class EagerSource:
    """Every region sampled up front until it has a valid sample or is given up; nothing drawn after."""

    def __init__(self, regions, world, sampling=None):
        self._inner = goal_source_for(tuple(regions), world, sampling)
        self.regions, self.stats = self._inner.regions, self._inner.stats
        self._done = False

    @property
    def sample_time(self) -> float:
        return self._inner.sample_time

    def exhausted(self) -> bool:
        return self._done

    def draw(self, n, rng, stop) -> list[GoalSample]:
        if self._done:
            return []
        out: list[GoalSample] = []
        todo = lambda: [j for j, st in enumerate(self.stats) if st.valid == 0 and not self._inner.region_exhausted(j)]
        # as many draws per round as regions, less those the reach prior dropped (they yield none): with the
        # prior on, 4 open regions of 512 at N = 256 got 128 goal states each, and eager 4-5 s instead of ~1 s
        n = sum(not st.unreachable for st in self.stats)
        while todo() and not stop.should_stop():
            out += self._inner.draw(n, rng, stop)
        self._done = not todo()
        return out


def _by_interpretation(regions) -> list[tuple]:
    """The regions grouped by interpretation, in grounding order."""
    groups: dict[str, list] = {}
    for r in regions:
        groups.setdefault(r.interpretation, []).append(r)
    return [tuple(g) for g in groups.values()]


def nearest_first_order(scene, world, regions) -> list[tuple]:
    """The regions grouped by interpretation, nearest object (or spot) first: the order nearest-first plans them in."""
    return sorted(_by_interpretation(regions), key=lambda g: _distance(scene, world, g))


def _distance(scene, world, group) -> float:
    """How far the group's object is from the car's start or the arm's base (nearest-first's order)."""
    obj = next(o for o in scene.objects if o.id == group[0].object)
    p = np.asarray(obj.pose.xyz, float)
    if scene.robot.model == "car":
        return float(np.hypot(*(p[:2] - np.asarray(world.start[:2], float))))
    base = np.asarray(scene.robot.base.xyz if scene.robot.base is not None else (0, 0, 0), float)
    return float(np.linalg.norm(p - base))


class _Stop(Exception):
    """Another independent planner has solved: stop this one."""


class _Turns:
    """Round-robin turns between planner threads (one runs at a time)."""

    def __init__(self, n: int):
        self.events = [threading.Event() for _ in range(n)]
        self.alive = list(range(n))
        self.lock = threading.Lock()
        self.winner = None

    def wait(self, i: int) -> None:
        self.events[i].wait()
        self.events[i].clear()
        if self.winner is not None:
            raise _Stop

    def pass_on(self, i: int, leaving: bool = False) -> None:
        with self.lock:
            k = self.alive.index(i)
            nxt = self.alive[(k + 1) % len(self.alive)]
            if leaving:
                self.alive.remove(i)
                if not self.alive or nxt == i:
                    return
        self.events[nxt].set()

    def finish(self, i: int) -> None:
        with self.lock:
            self.winner = i
        for e in self.events:
            e.set()


class _TurnChecker:
    """The world's checker, handing the turn on every TURN_CHECKS checks."""

    def __init__(self, world, turns: _Turns, i: int):
        self._world, self._turns, self._i, self._n = world, turns, i, 0

    def _tick(self):
        self._n += 1
        if self._n % TURN_CHECKS == 0:
            self._turns.pass_on(self._i)
            self._turns.wait(self._i)

    def __getattr__(self, name):
        attr = getattr(self._world, name)
        if name in ("config_free", "configs_free", "edge_free", "edge_fraction", "config_unpadded_free"):
            def ticking(*a, **k):
                self._tick()
                return attr(*a, **k)
            return ticking
        return attr


def planner_name(baseline: str, bidirectional: bool) -> str:
    """The bench's planner column for a baseline on one of our two planners."""
    return baseline + ("-bidirectional" if bidirectional else "")


def parse_planner(planner: str) -> tuple[str, bool] | None:
    """(baseline, bidirectional) of a planner column, or None when it is not a baseline's."""
    name, _, rest = planner.partition("-bidirectional") if planner.endswith("-bidirectional") else (planner, "", "")
    return (name, planner.endswith("-bidirectional")) if name in BASELINES else None


def run_baseline(name: str, scene, world, regions, space, settings, seed: int, call_budget: float = CALL_BUDGET,
                 sampling=None) -> tuple:
    """Run baseline ``name``: (PlanResult of the call that ended it, total seconds, iterations, goal attempts);
    ``sampling``: the goal sources' settings (None: their defaults; ``reach_prior`` drops regions for every method)."""
    rng = np.random.default_rng(seed)
    t0 = default_clock()
    consecutive = replace(settings, strategy=Strategy.CONSECUTIVE)
    if name in ("multiplexer", "eager"):  # one call; the source's making counts, as for our strategies (rrt.solve)
        source = (FirstRegionSource if name == "multiplexer" else EagerSource)(regions, world, sampling)
        r = solve(space, world, source, world.start, consecutive, rng, seed=seed, setup_s=default_clock() - t0)
        return r, r.time_s, r.iterations, sum(st.attempts for st in r.region_stats)
    if name == "nearest-first":
        groups = nearest_first_order(scene, world, regions)
        iters = attempts = 0
        r = None
        for g in groups:
            left = settings.time_limit - (default_clock() - t0)
            if left <= 0:
                break
            call = replace(settings, time_limit=min(call_budget, left))
            r = solve(space, world, goal_source_for(g, world, sampling), world.start, call, rng, seed=seed)
            iters += r.iterations
            attempts += sum(st.attempts for st in r.region_stats)
            if r.solved:
                break
        return r, default_clock() - t0, iters, attempts
    if name == "independent":
        return _independent(_by_interpretation(regions), world, space, settings, rng, seed, t0, sampling)
    raise ValueError(f"unknown baseline {name!r} (known: {', '.join(BASELINES)})")


def _independent(groups, world, space, settings, rng, seed, t0, sampling=None):
    turns = _Turns(len(groups))
    results: list = [None] * len(groups)
    rngs = rng.spawn(len(groups))

    def body(i):
        try:
            turns.wait(i)
            checker = _TurnChecker(world, turns, i)
            left = max(1e-3, settings.time_limit - (default_clock() - t0))  # one clock for all of them
            r = solve(space, checker, goal_source_for(groups[i], checker, sampling), world.start, replace(settings, time_limit=left),
                      rngs[i], seed=seed)
            results[i] = r
            if r.solved:
                turns.finish(i)
            else:
                turns.pass_on(i, leaving=True)
        except _Stop:
            pass

    threads = [threading.Thread(target=body, args=(i,), daemon=True) for i in range(len(groups))]
    for t in threads:
        t.start()
    turns.events[0].set()
    for t in threads:
        t.join()
    done = [r for r in results if r is not None]
    best = results[turns.winner] if turns.winner is not None else (done[-1] if done else None)
    iters = sum(r.iterations for r in done)
    attempts = sum(sum(st.attempts for st in r.region_stats) for r in done)
    return best, default_clock() - t0, iters, attempts
