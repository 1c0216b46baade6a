"""Where one planner iteration's time goes (#31): ``lazyground bench --iteration-profile``.

Two passes over the same seeds of each scene, through ``api.plan`` on a prebuilt world:

1. plain: the search's own timer (``PlanResult.time_s``) per iteration, the true figure;
2. timed: the shares of the planner's steps, wrapped in timers (exclusive time: a step's callees count as
   theirs), split into nearest neighbours, the space (sampling, steering, interpolation,
   distances), collision checks (the planner's calls into the checker, its glue included),
   tree bookkeeping, goal selection and credit (the strategy), goal sampling (IK, its
   checks included), joins (the re-check of a candidate path) and the rest of the loop.
   The wrappers' own cost (measured, per call) is taken off each step's share; the shares
   (medians over runs) split the plain pass's time per iteration.

Only the search is split; grounding, motion and the rest of a request are
``tools/request_profile.py``'s. Compare figures taken in one run (the machine's load
scales them all).
"""

from __future__ import annotations

import statistics
import time
from dataclasses import dataclass

STEPS = ("nn", "space", "checks", "tree", "strategy", "join", "loop", "goal sampling")
PER_ITERATION = STEPS[:-1]  # goal sampling (IK) is per goal sample drawn, not per iteration: per run


def _targets():
    """(class or module, attribute, step) of everything timed."""
    from lazyground.drake.world import DrakeWorld
    from lazyground.planning import birrt, search
    from lazyground.planning.motion_validator import MotionValidator
    from lazyground.planning.space import ConfigSpace
    from lazyground.planning.tree import Tree

    # (a Reeds-Shepp car's nearest-node query and its step are one compiled call: _car_nearest, #33)
    out = [(Tree, m, "nn") for m in ("nearest", "nearest_k", "_car_nearest")]
    out += [(Tree, m, "tree") for m in ("add", "add_root", "chain", "prune")]
    out += [(ConfigSpace, m, "space") for m in ("sample", "steer", "interpolate", "distance", "within_bounds")]
    out += [(MotionValidator, m, "checks") for m in ("edge_free", "edge_fraction")]
    out += [(DrakeWorld, m, "checks") for m in ("config_free", "config_unpadded_free", "configs_free")]
    out += [(search.Search, m, "strategy") for m in ("select", "reward", "penalize", "have_samples")]
    out += [(search.Search, "draw", "goal sampling")]
    out += [(birrt, "_join", "join"), (search.Search, "first_invalid_segment", "join")]
    out += [(birrt, "_credit", "strategy")]
    return out


class _Timers:
    """Exclusive wall time and calls per step while installed."""

    def __init__(self):
        self.seconds = dict.fromkeys(STEPS, 0.0)
        self.calls = dict.fromkeys(STEPS, 0)
        self._stack: list[list[float]] = []
        self._saved: list[tuple] = []
        self._sampling = [0]  # inside goal sampling: its checks and kinematics are its own
        self._active = [False]  # inside a search (install() ties it to a Search's life)

    def install(self) -> None:
        from lazyground.planning.search import Search

        for owner, attr, step in _targets():
            inner = owner.__dict__[attr] if isinstance(owner, type) else getattr(owner, attr)
            self._saved.append((owner, attr, inner))
            setattr(owner, attr, self.wrap(inner, step))
        # only a search's own calls count (not the motion step's checks after it): from a Search's
        # construction to its result
        active = self._active
        init, result = Search.__dict__["__init__"], Search.__dict__["result"]
        self._saved += [(Search, "__init__", init), (Search, "result", result)]

        def opened(search, *args, **kwargs):
            init(search, *args, **kwargs)
            active[0] = True

        def closed(search, *args, **kwargs):
            try:
                return result(search, *args, **kwargs)
            finally:
                active[0] = False

        Search.__init__, Search.result = opened, closed

    def remove(self) -> None:
        for owner, attr, inner in reversed(self._saved):
            setattr(owner, attr, inner)
        self._saved.clear()

    def wrap(self, inner, step: str):
        """``inner`` timed as ``step``."""
        stack, seconds, calls, clock, sampling = self._stack, self.seconds, self.calls, time.perf_counter, self._sampling
        active = self._active
        mark = int(step == "goal sampling")

        def timed(*args, **kwargs):
            if not active[0] or sampling[0] and not mark:
                return inner(*args, **kwargs)
            sampling[0] += mark
            inside = [0.0]
            stack.append(inside)
            t0 = clock()
            try:
                return inner(*args, **kwargs)
            finally:
                dt = clock() - t0
                sampling[0] -= mark
                stack.pop()
                seconds[step] += dt - inside[0]
                calls[step] += 1
                if stack:
                    stack[-1][0] += dt

        return timed

    def take(self) -> tuple[dict, dict]:
        out = dict(self.seconds), dict(self.calls)
        for k in STEPS:
            self.seconds[k], self.calls[k] = 0.0, 0
        return out


def _wrapper_cost(repeats: int = 5000, tries: int = 7) -> tuple[float, float]:
    """(seconds a timed call adds to its caller's share, to its own share), measured here from the least
    of ``tries`` readings of each loop (a loaded machine's pauses only ever add)."""

    class Probe:
        def f(self):
            return None

    clock, plain = time.perf_counter, Probe()
    bare = total = own = float("inf")
    for _ in range(tries):
        timers = _Timers()
        wrapped = timers.wrap(Probe.f, "loop")
        t0 = clock()
        for _ in range(repeats):
            plain.f()
        bare = min(bare, clock() - t0)
        t0 = clock()
        for _ in range(repeats):
            wrapped(plain)
        total = min(total, clock() - t0)
        own = min(own, timers.seconds["loop"])
    return max(0.0, (total - own) / repeats), max(0.0, (own - bare) / repeats)


@dataclass(frozen=True)
class SceneProfile:
    scene: str
    runs: int
    solved: int
    iterations: float  # median per run
    us_per_iteration: float  # median of the plain pass's (time_s - goal_sampling_s) / iterations
    goal_sampling_ms: float  # median per run
    checks_per_iteration: float
    us_per_check: float  # median of collision_s / collision_checks (the plain pass)
    split_us: dict  # step -> microseconds per iteration: the plain pass's, split as the timed pass's medians share it
    calls_per_iteration: dict  # step -> wrapped calls per iteration
    timer_us: float  # what one timed call adds (measured; taken off the shares)


def profile_scene(key: str, seeds: range, request: str | None = None, **overrides) -> SceneProfile:
    """Both passes on one scene (a name or file) over ``seeds``; ``overrides``: settings for ``api.plan``."""
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    scene = load_scene(key)
    world = DrakeWorld(scene, visual=False)
    request = request or scene.expect[0].request
    api.plan(scene, request, seed=seeds.stop + 100, world=world, **overrides)  # warm-up: first-call costs are not an iteration's
    plain = [api.plan(scene, request, seed=s, world=world, **overrides).result for s in seeds]
    to_caller, to_own = _wrapper_cost()
    timers, split, calls = _Timers(), [], []
    timers.install()
    try:
        for s in seeds:
            r = api.plan(scene, request, seed=s, world=world, **overrides).result
            sec, n = timers.take()
            its = max(r.iterations, 1)
            used = {k: max(0.0, sec[k] - n[k] * to_own) for k in STEPS if k != "loop"}
            used["loop"] = r.time_s - sum(used.values()) - sum(n.values()) * (to_own + to_caller)  # may come out < 0: noise
            loop_s = sum(v for k, v in used.items() if k != "goal sampling") or 1.0
            split.append({k: v / loop_s for k, v in used.items() if k != "goal sampling"})  # fractions
            calls.append({k: n[k] / its for k in STEPS})
    finally:
        timers.remove()
    med = statistics.median
    us = med((r.time_s - r.goal_sampling_s) / max(r.iterations, 1) * 1e6 for r in plain)
    return SceneProfile(
        scene=scene.name, runs=len(plain), solved=sum(r.solved for r in plain),
        iterations=med(r.iterations for r in plain),
        us_per_iteration=us,
        goal_sampling_ms=med(r.goal_sampling_s * 1e3 for r in plain),
        checks_per_iteration=med(r.collision_checks / max(r.iterations, 1) for r in plain),
        us_per_check=med(r.collision_s / max(r.collision_checks, 1) * 1e6 for r in plain),
        split_us={k: med(x[k] for x in split) * us for k in PER_ITERATION},
        calls_per_iteration={k: med(x[k] for x in calls) for k in STEPS},
        timer_us=(to_own + to_caller) * 1e6,
    )


def report(profiles: list[SceneProfile]) -> str:
    """A Markdown table: per scene, the search's time per iteration and its split."""
    head = ("| scene | runs (solved) | iterations | goal sampling ms | µs / iteration | checks / iteration | µs / check | "
            + " | ".join(f"{k} µs" for k in PER_ITERATION) + " | timed calls / iteration |")
    lines = ["Search time per iteration, goal sampling (IK, per run) apart (medians over runs; the split from a "
             "second, timed pass's shares, the timers' own cost removed; 'loop' is the search's time outside every timed step).",
             "", head, "|" + "---|" * (8 + len(PER_ITERATION))]
    for p in profiles:
        split = " | ".join(f"{p.split_us[k]:.1f}" for k in PER_ITERATION)
        calls = sum(v for k, v in p.calls_per_iteration.items() if k != "goal sampling")
        lines.append(f"| {p.scene} | {p.runs} ({p.solved}) | {p.iterations:.0f} | {p.goal_sampling_ms:.1f} | "
                     f"{p.us_per_iteration:.1f} | {p.checks_per_iteration:.2f} | {p.us_per_check:.1f} | {split} | {calls:.1f} |")
    if profiles:
        lines += ["", f"One timed call costs {statistics.median(p.timer_us for p in profiles):.2f} µs (taken off; a "
                      "negative 'loop' means the loop's own share is within that correction's noise)."]
    return "\n".join(lines) + "\n"
