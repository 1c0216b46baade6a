"""Where one ``api.plan`` request's time goes on the Fetch scenes (#31): a per-phase table and a cProfile.

Run from the checkout's root (cwd comes first on sys.path)::

    nice python3 tools/request_profile.py                      # phases, median over seeds 0-9
    nice python3 tools/request_profile.py --cprofile 25        # plus the top 25 functions by own time
    nice python3 tools/request_profile.py --scene fetch_cans_1 --path

The world is built once per scene (as a bench worker does) and one warm-up request is made, so the table
shows a request as a user of a prebuilt world waits for it. ``--path`` passes the scene's name to
``api.plan`` (it loads the scene file each call, as the CLI and the quick-start do); the default passes the
loaded Scene. Phases: total_s (the report's: wall less world build) split into grounding, search (IK goal
sampling is part of it, shown apart), motion and the rest (everything outside those timers).
"""

from __future__ import annotations

import argparse
import cProfile
import io
import pstats
import statistics
import sys
import time
from pathlib import Path

FETCH = ("fetch_cans_1", "fetch_cans_2", "fetch_boxes_3")


def request_of(scene) -> str:
    return scene.expect[0].request


class Phases:
    """Wall time per wrapped function over one request (the per-phase timer); wrappers nest, the caller's
    share excludes its callees'."""

    def __init__(self):
        self.totals: dict[str, float] = {}
        self._stack: list[list] = []

    def wrap(self, module, attr: str, name: str) -> None:
        inner = getattr(module, attr)

        def timed(*args, **kwargs):
            frame = [0.0]  # time spent in wrapped callees
            self._stack.append(frame)
            t0 = time.perf_counter()
            try:
                return inner(*args, **kwargs)
            finally:
                dt = time.perf_counter() - t0
                self._stack.pop()
                self.totals[name] = self.totals.get(name, 0.0) + dt - frame[0]
                if self._stack:
                    self._stack[-1][0] += dt

        setattr(module, attr, timed)

    def take(self) -> dict[str, float]:
        out, self.totals = self.totals, {}
        return out


def install_phases() -> Phases:
    """Wrap the request's steps (api.plan, tasks.reach.run and what they call) in timers."""
    import grounding
    from lazyground import api
    from lazyground.tasks import reach

    phases = Phases()
    phases.wrap(api, "load_scene", "load scene")
    phases.wrap(api, "run_settings", "settings")
    phases.wrap(grounding, "ground", "grounding")
    phases.wrap(reach, "make_goal_source", "goal source")
    phases.wrap(reach, "solve", "solve")
    phases.wrap(reach, "post_process", "post-process")
    phases.wrap(reach, "sweep_note", "notes")
    phases.wrap(reach, "improvement_notes", "notes")
    return phases


def profile_scene(name: str, seeds: int, by_path: bool, top: int, phases: Phases | None = None) -> dict:
    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.scene import load_scene

    scene = load_scene(name)
    world = DrakeWorld(scene, visual=False)
    request = request_of(scene)
    arg = name if by_path else scene
    api.plan(arg, request, seed=100, world=world)  # warm-up: first-call costs are not a request's
    if phases is not None:
        phases.take()
    rows, parts = [], []
    prof = cProfile.Profile(time.process_time) if top else None  # CPU time: the machine's load does not skew it
    for seed in range(seeds):
        t0 = time.perf_counter()
        if prof is not None:
            prof.enable()
        r = api.plan(arg, request, seed=seed, world=world)
        if prof is not None:
            prof.disable()
        wall = time.perf_counter() - t0
        split = r.total_split_s
        res = r.result
        if phases is not None:
            part = phases.take()
            part["solve"] -= res.time_s  # the search's own timer; the remainder is outside it
            part["post-process"] -= split["motion"]
            part["other"] = r.total_s - split["search"] - split["motion"] - sum(part.values())
            parts.append(part)
        rows.append(dict(wall=wall, total=r.total_s, **split, ik=res.goal_sampling_s, checks=res.collision_checks,
                         per_check=res.collision_s / max(res.collision_checks, 1), iterations=res.iterations,
                         solved=res.status.value == "solved"))
    med = {k: statistics.median(r[k] for r in rows) for k in rows[0] if k != "solved"}
    med["solved"] = sum(r["solved"] for r in rows)
    if parts:
        med["phases"] = {k: statistics.median(p.get(k, 0.0) for p in parts) for k in parts[0]}
    if prof is not None:
        out = io.StringIO()
        pstats.Stats(prof, stream=out).sort_stats("tottime").print_stats(top)
        med["profile"] = out.getvalue()
    return med


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", action="append", help="a Fetch scene (default: all three)")
    p.add_argument("--seeds", type=int, default=10)
    p.add_argument("--path", action="store_true", help="pass the scene's name to api.plan (it loads the file)")
    p.add_argument("--phases", action="store_true", help="also time the steps outside the search and motion timers")
    p.add_argument("--cprofile", type=int, default=0, metavar="N", help="also print the N functions with most own time")
    args = p.parse_args()
    sys.path.insert(0, str(Path.cwd()))
    ms = lambda s: f"{s * 1e3:7.1f}"  # noqa: E731
    print(f"median over seeds 0-{args.seeds - 1}, ms ({'scene by name' if args.path else 'loaded Scene'}):")
    print(f"{'scene':15} {'total':>7} {'ground':>7} {'search':>7} {'(IK)':>7} {'motion':>7} {'rest':>7} {'checks':>7} "
          f"{'us/chk':>7} {'iters':>6} solved")
    profiles, rest = [], []
    phases = install_phases() if args.phases else None
    for name in args.scene or FETCH:
        m = profile_scene(name, args.seeds, args.path, args.cprofile, phases)
        print(f"{name:15} {ms(m['total'])} {ms(m['grounding'])} {ms(m['search'])} {ms(m['ik'])} {ms(m['motion'])} {ms(m['rest'])} "
              f"{m['checks']:7.0f} {m['per_check'] * 1e6:7.1f} {m['iterations']:6.0f} {m['solved']}/{args.seeds}",
              flush=True)
        if "profile" in m:
            profiles.append((name, m["profile"]))
        if "phases" in m:
            rest.append((name, m["phases"]))
    if rest:
        names = list(rest[0][1])
        print("\noutside the search and motion timers, median ms per request ('solve'/'post-process': their wall time"
              " less the search's/motion's own timers; 'other': the rest of total_s):")
        print(f"{'scene':15} " + " ".join(f"{n:>12}" for n in names))
        for name, ph in rest:
            print(f"{name:15} " + " ".join(f"{ph[n] * 1e3:12.2f}" for n in names))
    for name, text in profiles:
        print(f"\n== {name}: cProfile over {args.seeds} requests ==\n{text}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
