"""The planner loop's own time per iteration, checks and goal sampling replayed from a record (#31, Deliver 2).

Run from the checkout's root (cwd comes first on sys.path)::

    nice python3 tools/loop_replay.py                      # Fetch scenes, seeds 0-4, 20 replays each
    nice python3 tools/loop_replay.py --scenes fetch_boxes_3 --seeds 10 --replays 50 --profile
    # checkouts compared in one interleaved run (A B B A), each in its own process from its own root;
    # runs on the issue's base 703386a too (its solve() has no stop condition: the replay lifts time_limit)
    nice python3 tools/loop_replay.py --checkouts /tmp/base_703386a,. --rounds 2 --seeds 10 --replays 10 --profile
    # per-iteration overhead apart from the per-run fixed cost: loop CPU per run = fixed + slope x iterations
    nice python3 tools/loop_replay.py --checkouts /tmp/base_703386a,. --seeds 20 --replays 5 --fit
    # the same scene with longer runs (any api.plan override, on every checkout): the one-tree planner
    nice python3 tools/loop_replay.py --checkouts /tmp/base_703386a,. --scenes fetch_cans_2 --set algorithm=rrt --fit

Each seed is planned once for real (``api.plan`` on a prebuilt world) while the checker's answers and the
goal source's samples (with the generator's state after each draw) are recorded; the search is then run
again ``--replays`` times against the record: the same iterations, nodes and path, with every collision
check and IK draw a list lookup. Its CPU time (``time.process_time``, so a busy machine's waits do not count)
per iteration is the loop's overhead outside checks and goal sampling: nearest neighbours, steering, tree
and strategy bookkeeping, Python calls per edge. Printed per scene: the median over seeds of the fastest
replay (the least disturbed), and the search's real figures for scale. A replay that does not end as the
real run did is reported (the record would not fit the code). ``us/it pooled`` is the seeds' loop CPU summed over
their iterations summed (short runs weigh less than in the median). ``--profile`` adds one cProfiled replay per
seed, its own time by planner file (numpy and builtins count for the planner file that called them), scaled
to the unprofiled CPU (cProfile inflates Python calls ~5x, so the shares lean towards call-heavy parts).
``--fit`` fits each seed's loop CPU (its fastest replay over the rounds) as fixed + slope x iterations (Theil-Sen;
least squares beside it), with 95 % bootstrap intervals over seeds for each checkout's slope and fixed part and
for their ratios to the first checkout's: the slope is the per-iteration overhead, free of the per-run costs
(set-up, goal roots, the path's re-check) that dominate a scene whose runs are a few iterations long.
"""

from __future__ import annotations

import argparse
import copy
import statistics
import sys
import time
from pathlib import Path

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")
ANSWERS = ("config_free", "config_unpadded_free", "configs_free", "edge_free", "edge_fraction")


class OffRecord(Exception):
    """A replay asked more than the record holds: it did not run as the recorded plan."""


class Recorder:
    """A checker or goal source whose answers are logged in call order (record) or read back (replay)."""

    def __init__(self, inner=None, log: list | None = None):
        self._inner, self._log, self._replay = inner, [] if log is None else log, log is not None
        self._at = 0
        self.check_time = self.checks = 0

    def _answer(self, name, *args):
        if self._replay:
            if self._at == len(self._log):
                raise OffRecord(name)
            out = self._log[self._at]
            self._at += 1
            return out
        out = getattr(self._inner, name)(*args)
        self._log.append(copy.deepcopy(out))
        return out

    def __getattr__(self, name):
        if name in ANSWERS:
            return lambda *args, _n=name: self._answer(_n, *args)
        raise AttributeError(name)


class GoalRecorder(Recorder):
    """Goal draws: the samples and the generator's state after each (a replay restores it)."""

    def __init__(self, inner=None, log: list | None = None, regions=(), stats=()):
        super().__init__(inner, log)
        self.regions = inner.regions if inner is not None else regions
        self.stats = inner.stats if inner is not None else stats
        self.sample_time = 0.0

    @property
    def total_attempts(self):
        return self._answer("total_attempts_")

    def total_attempts_(self):
        return getattr(self._inner, "total_attempts", None)

    def exhausted(self):
        return self._answer("exhausted_")

    def exhausted_(self):
        return self._inner.exhausted()

    def draw(self, n, rng, stop):
        if self._replay:  # (the log is a fresh copy per replay: nothing is copied while the replay is timed)
            if self._at == len(self._log):
                raise OffRecord("draw")
            samples, state = self._log[self._at]
            self._at += 1
            rng.bit_generator.state = state
            return samples
        out = self._inner.draw(n, rng, stop)
        self._log.append((copy.deepcopy(out), copy.deepcopy(rng.bit_generator.state)))
        return out


def record(scene_name: str, seed: int, world, scene, overrides: dict | None = None) -> dict:
    """One real plan (with the API's setting ``overrides``), its solve() call's arguments and logs."""
    from lazyground import api
    from lazyground.planning import rrt

    rec = {}
    real_solve = rrt.solve

    def recording(space, checker, goals, start, settings, rng, seed=None, keep_tree=False, **stop):
        if "space" in rec:  # (a later search of the same request, e.g. an anytime improvement: the first is replayed)
            return real_solve(space, checker, goals, start, settings, rng, seed, keep_tree, **stop)
        ck, gs = Recorder(checker), GoalRecorder(goals)
        rec.update(space=space, start=start.copy(), settings=settings, state=copy.deepcopy(rng.bit_generator.state),
                   seed=seed, checks=ck._log, goals=gs._log, regions=goals.regions, stats=copy.deepcopy(goals.stats))
        r = real_solve(space, ck, gs, start, settings, rng, seed, keep_tree, **stop)
        rec["iterations"], rec["path"] = r.iterations, r.path
        return r

    targets = [m for k, m in list(sys.modules.items()) if k.startswith("lazyground") and getattr(m, "solve", None) is real_solve]
    for m in targets:
        m.solve = recording
    try:
        report = api.plan(scene, scene.expect[0].request, seed=seed, world=world, **(overrides or {}))
    finally:
        for m in targets:
            m.solve = real_solve
    rec["report"] = report
    return rec


def replay(rec: dict, prof=None) -> tuple[float, bool]:
    """(CPU seconds of one replayed solve, whether it ended as the recorded run); ``prof``: a cProfile.Profile
    enabled around the solve only."""
    import dataclasses
    import inspect

    import numpy as np

    from lazyground.planning import rrt

    ck = Recorder(log=rec["checks"])
    gs = GoalRecorder(log=copy.deepcopy(rec["goals"]), regions=rec["regions"], stats=copy.deepcopy(rec["stats"]))
    rng = np.random.default_rng()
    rng.bit_generator.state = copy.deepcopy(rec["state"])
    settings, stop = rec["settings"], {}
    if "stop" in inspect.signature(rrt.solve).parameters:
        from lazyground.planning.stop import StopCondition

        stop["stop"] = StopCondition.after(1e9, max_iterations=settings.max_iterations)
    else:  # (703386a, the base: the search's deadline is settings.time_limit)
        settings = dataclasses.replace(settings, time_limit=1e9)
    if prof is not None:
        prof.enable()
    t0 = time.process_time()
    try:
        r = rrt.solve(rec["space"], ck, gs, rec["start"], settings, rng, rec["seed"], False, **stop)
    except OffRecord:
        return time.process_time() - t0, False
    finally:
        if prof is not None:
            prof.disable()
    dt = time.process_time() - t0
    same = r.iterations == rec["iterations"] and (
        (r.path is None) == (rec["path"] is None) and (r.path is None or np.array_equal(r.path, rec["path"])))
    return dt, same


CATEGORIES = (("nn", ("planning/nn.py",)), ("space", ("planning/space.py",)), ("tree", ("planning/tree.py",)),
              ("strategy", ("planning/strategies.py", "planning/weights.py", "planning/cover.py")),
              ("search", ("planning/search.py", "planning/stop.py")), ("loop", ("planning/birrt.py", "planning/rrt.py")),
              ("stand-ins", ("loop_replay.py",)))


def _category(func) -> str | None:
    path = func[0].replace("\\", "/")
    for name, files in CATEGORIES:
        if any(path.endswith(f) for f in files):
            return name
    return None


def breakdown(stats) -> dict[str, float]:
    """cProfile stats as seconds of own time per category: a function outside the planner (numpy, builtins)
    counts for the planner file that called it, split by its callers' shares."""
    memo: dict = {}

    def shares(func, depth=0) -> dict[str, float]:  # the fraction of func's time that each category caused
        if func in memo:
            return memo[func]
        cat = _category(func)
        if cat is not None or depth > 30:
            out = {cat or "other": 1.0}
        else:
            memo[func] = {"other": 1.0}  # (a cycle)
            callers = stats.stats[func][4]
            total = sum(c[2] for c in callers.values()) or sum(c[1] for c in callers.values()) or 1.0
            out = {}
            for caller, c in callers.items():
                w = (c[2] or (c[1] if not any(x[2] for x in callers.values()) else 0.0)) / total
                for k, v in shares(caller, depth + 1).items():
                    out[k] = out.get(k, 0.0) + w * v
            out = out or {"other": 1.0}
        memo[func] = out
        return out

    got: dict[str, float] = {}
    for func, (_cc, _nc, tt, _ct, _callers) in stats.stats.items():
        for k, v in shares(func).items():
            got[k] = got.get(k, 0.0) + tt * v
    return got


def measure(scenes, seeds: int, replays: int, profile: bool, overrides: dict | None = None) -> dict:
    """Per scene, per seed: iterations, the fastest replay's CPU seconds, replays that matched, search less IK;
    with ``profile`` also one cProfiled replay per seed broken down by category (seconds)."""
    import cProfile
    import pstats

    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    out = {}
    for name in scenes:
        scene = load_scene(name)
        world = DrakeWorld(scene, visual=False)
        record(name, 1000, world, scene, overrides)  # warm-up
        rows = []
        for seed in range(seeds):
            rec = record(name, seed, world, scene, overrides)
            r = rec["report"].result
            best, ok = float("inf"), 0
            for _ in range(replays):
                dt, same = replay(rec)
                best, ok = min(best, dt), ok + same
            row = dict(seed=seed, iterations=rec["iterations"], best_s=best, ok=ok, replays=replays,
                       search_ms=(r.time_s - r.goal_sampling_s) * 1e3)
            if profile:
                prof = cProfile.Profile(time.process_time)
                row["profiled_s"] = replay(rec, prof)[0]
                row["profile"] = breakdown(pstats.Stats(prof))
            rows.append(row)
        out[name] = rows
    return out


def summary(rows: list[dict]) -> dict:
    its = [r["iterations"] for r in rows]
    return dict(iterations=statistics.median(its),
                us_it=statistics.median(r["best_s"] / max(r["iterations"], 1) * 1e6 for r in rows),
                pooled_us_it=sum(r["best_s"] for r in rows) / max(sum(its), 1) * 1e6,
                ms_run=statistics.median(r["best_s"] * 1e3 for r in rows),
                search_ms=statistics.median(r["search_ms"] for r in rows),
                ok=sum(r["ok"] for r in rows))


def theil_sen(x, y) -> tuple[float, float]:
    """(fixed, slope) of y = fixed + slope x: the median of the pairwise slopes, then the median intercept."""
    import numpy as np

    x, y = np.asarray(x, float), np.asarray(y, float)
    i, j = np.triu_indices(len(x), 1)
    keep = x[i] != x[j]
    slope = float(np.median((y[j] - y[i])[keep] / (x[j] - x[i])[keep])) if keep.any() else 0.0
    return float(np.median(y - slope * x)), slope


def least_squares(x, y) -> tuple[float, float]:
    import numpy as np

    slope, fixed = np.polyfit(np.asarray(x, float), np.asarray(y, float), 1)
    return float(fixed), float(slope)


def per_seed(runs: list[dict], name: str) -> tuple[list[int], list[float]]:
    """Each seed's iterations and its fastest replay over the rounds (seconds); seeds whose replays did not all
    end as the recorded run are left out."""
    rows = [run[name] for run in runs]
    keep = [k for k in range(len(rows[0])) if all(rr[k]["ok"] == rr[k]["replays"] for rr in rows)]
    return [rows[0][k]["iterations"] for k in keep], [min(rr[k]["best_s"] for rr in rows) for k in keep]


def print_fit(name: str, fits: dict[str, tuple[list[int], list[float]]], base: str, resamples: int = 2000) -> None:
    """Loop CPU per run = fixed + slope x iterations, per checkout (Theil-Sen over seeds; least squares beside it),
    with 95 % bootstrap intervals (seeds resampled) of the slope, the fixed part and their ratios to ``base``'s."""
    import numpy as np

    rng = np.random.default_rng(0)
    boot: dict[str, np.ndarray] = {}
    print("  fit, loop CPU per run = fixed + slope x iterations (Theil-Sen over the seeds whose replays matched, "
          "[95 % bootstrap], least squares after /):")
    for c, (x, y) in fits.items():
        x, y = np.asarray(x, float), np.asarray(y, float) * 1e3
        fixed, slope = theil_sen(x, y)
        lf, ls = least_squares(x, y) if len(set(x.tolist())) > 1 else (float("nan"), float("nan"))
        draws = []
        for _ in range(resamples):
            k = rng.integers(len(x), size=len(x))
            draws.append(theil_sen(x[k], y[k]))
        boot[c] = np.array(draws)
        lo, hi = np.percentile(boot[c], [2.5, 97.5], axis=0)
        print(f"    {c[-30:]:30} slope {slope * 1e3:6.1f} us/it [{lo[1] * 1e3:.1f}, {hi[1] * 1e3:.1f}] / {ls * 1e3:.1f}, "
              f"fixed {fixed:6.2f} ms [{lo[0]:.2f}, {hi[0]:.2f}] / {lf:.2f}; {len(x)} seeds, iterations {int(x.min())}-{int(x.max())}")
    for c in fits:
        if c == base:
            continue
        fixed_b, slope_b = theil_sen(*[np.asarray(v, float) for v in fits[base]])
        fixed_c, slope_c = theil_sen(*[np.asarray(v, float) for v in fits[c]])
        r = boot[c] / boot[base]
        lo, hi = np.percentile(r, [2.5, 97.5], axis=0)
        print(f"    {c[-30:]} / {base[-30:]}: slope {slope_c / slope_b:.2f} [{lo[1]:.2f}, {hi[1]:.2f}], "
              f"fixed {fixed_c / fixed_b:.2f} [{lo[0]:.2f}, {hi[0]:.2f}]")


def print_profile(name: str, rows: list[dict]) -> None:
    its = max(sum(r["iterations"] for r in rows), 1)
    got: dict[str, float] = {}
    for r in rows:
        for k, v in r["profile"].items():
            got[k] = got.get(k, 0.0) + v
    cats = [c for c, _ in CATEGORIES] + ["other"]
    scale = sum(r["best_s"] for r in rows) / max(sum(got.values()), 1e-12)
    print(f"  {name} us/it by cProfile's shares, scaled to the unprofiled {sum(r['best_s'] for r in rows) / its * 1e6:.1f} "
          f"(profiled {sum(r['profiled_s'] for r in rows) / its * 1e6:.0f}): "
          + ", ".join(f"{c} {got.get(c, 0.0) * scale / its * 1e6:.1f}" for c in cats))


def interleaved(args) -> int:
    """Run this tool in each checkout in turn (A B A B ...), one process each, and compare."""
    import json
    import subprocess

    checkouts = [str(Path(c).resolve()) for c in args.checkouts.split(",")]
    runs: dict[str, list[dict]] = {c: [] for c in checkouts}
    for rnd in range(args.rounds):
        for c in (checkouts if rnd % 2 == 0 else checkouts[::-1]):
            cmd = [sys.executable, str(Path(__file__).resolve()), "--json", "--scenes", args.scenes,
                   "--seeds", str(args.seeds), "--replays", str(args.replays)] + (["--profile"] if args.profile else [])
            cmd += [a for kv in args.set for a in ("--set", kv)]
            t0 = time.strftime("%H:%M:%S", time.gmtime())
            done = subprocess.run(cmd, cwd=c, capture_output=True, text=True)
            if done.returncode:
                raise SystemExit(f"{c}: {' '.join(cmd[1:])} failed:\n{done.stderr[-2000:]}")
            runs[c].append(json.loads(done.stdout))
            print(f"# round {rnd + 1} {c} {t0}-{time.strftime('%H:%M:%S', time.gmtime())} UTC, "
                  f"load {open('/proc/loadavg').read().split()[0] if Path('/proc/loadavg').exists() else '?'}", flush=True)
    base = checkouts[0]
    for name in args.scenes.split(","):
        print(f"\n{name}")
        print(f"  {'checkout':40} {'iters/seed':>24} {'us/it (med)':>16} {'us/it pooled':>16} {'ms/run':>16} ok")
        pooled = {}
        for c in checkouts:
            ss = [summary(run[name]) for run in runs[c]]
            pooled[c] = statistics.median(s["pooled_us_it"] for s in ss)
            its = ",".join(str(r["iterations"]) for r in runs[c][0][name])
            cols = [" / ".join(f"{s[k]:.{d}f}" for s in ss) for k, d in (("us_it", 0), ("pooled_us_it", 0), ("ms_run", 1))]
            print(f"  {c[-40:]:40} {its[:24]:>24} {cols[0]:>16} {cols[1]:>16} {cols[2]:>16} "
                  f"{min(s['ok'] for s in ss)}/{args.seeds * args.replays}")
        for c in checkouts[1:]:
            print(f"  pooled us/it, median over rounds: {c[-30:]} / {base[-30:]} = {pooled[c] / pooled[base]:.2f}")
        if args.fit:
            print_fit(name, {c: per_seed(runs[c], name) for c in checkouts}, base)
        if args.profile:
            for c in checkouts:
                print_profile(c[-30:], runs[c][-1][name])
    return 0


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scenes", default=",".join(FETCH))
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--replays", type=int, default=20)
    p.add_argument("--profile", action="store_true", help="also one cProfiled replay per seed, by category")
    p.add_argument("--json", action="store_true", help="per-seed figures as JSON (for --checkouts)")
    p.add_argument("--checkouts", help="comma-separated checkout roots: run each in turn, interleaved")
    p.add_argument("--rounds", type=int, default=2, help="with --checkouts: runs per checkout (A B B A ...)")
    p.add_argument("--fit", action="store_true",
                   help="fit loop CPU per run = fixed + slope x iterations over the seeds (Theil-Sen, bootstrap intervals)")
    p.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                   help="a setting for every plan, as api.plan's overrides (e.g. algorithm=rrt for long runs); repeatable")
    args = p.parse_args()
    if args.checkouts:
        return interleaved(args)
    sys.path.insert(0, str(Path.cwd()))
    import json

    got = measure(args.scenes.split(","), args.seeds, args.replays, args.profile, dict(_setting(kv) for kv in args.set))
    if args.json:
        print(json.dumps(got))
        return 0
    print(f"{'scene':15} {'iters':>6} {'loop us/it':>10} {'us/it pooled':>12} {'loop ms/run':>11} {'search-IK ms':>12} {'replays ok':>10}")
    for name, rows in got.items():
        s = summary(rows)
        print(f"{name:15} {s['iterations']:6.0f} {s['us_it']:10.1f} {s['pooled_us_it']:12.1f} {s['ms_run']:11.2f} "
              f"{s['search_ms']:12.1f} {s['ok']:>5}/{args.seeds * args.replays}", flush=True)
        if args.fit:
            print_fit(name, {".": per_seed([got], name)}, ".")
        if args.profile:
            print_profile(name, rows)
    return 0


def _setting(kv: str) -> tuple[str, object]:
    """``key=value`` with the value as an int, a float or a string."""
    key, _, value = kv.partition("=")
    for kind in (int, float):
        try:
            return key, kind(value)
        except ValueError:
            pass
    return key, value


if __name__ == "__main__":
    raise SystemExit(main())
