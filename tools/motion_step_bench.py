"""The motion step (shortcut, fine re-check, timing) per Fetch scene and per sub-phase, code trees A/B interleaved (#31).

Each tree (a checkout of lazyground, e.g. main and a branch) runs in its own worker process with its
own prebuilt worlds. The first tree plans seeds 0..N-1 per scene with ``api.plan``; what its motion
step received (the raw path, the goal's approach, the generator's state) is then replayed by every
tree's ``motion_for_world``, request after request, trees alternating (ABBA), so both time the same
inputs on the same machine load. Sub-phases are the tree's own functions, timed where they exist
(a "-" where a tree has no such function), in CPU time: greedy pass, random shortcuts, relaxation, the shortcut's
fine check, TOPP-RA, the timing's dense check, the limits. Every result is re-checked independently:
the path every resolution / validation_factor and at half that, the trajectory as the tests do, each by
its own tree's code and again by the first tree's (the last column: independent of the code under test).
Trees as old as 703386a (the start of #31: ``make_motion`` took a PlannerSettings) run too.

    git -C /work/main worktree add /tmp/base 703386a
    nice python3 tools/motion_step_bench.py --tree before=/tmp/base --tree now=.
    nice python3 tools/motion_step_bench.py --tree main=/work/main --tree motion=.
    nice python3 tools/motion_step_bench.py --tree before=/tmp/base --tree main=/work/main --tree now=.  (each against the last)
    python3 tools/motion_step_bench.py --tree main=/work/main --tree motion=. --seeds 5 --scenes fetch_cans_1

Quiet machine: ~2 min for 3 scenes x 20 seeds x 2 trees (world builds included).
"""

from __future__ import annotations

import argparse
import os
import pickle
import subprocess
import sys
import time

SCENES = {"fetch_cans_1": "pick up a can", "fetch_cans_2": "pick up a can", "fetch_boxes_3": "pick up a box"}
# (label, module, attribute): what each sub-phase times; a class method as "Class.method"
PHASES = [
    ("greedy", "lazyground.motion.shortcut", "_greedy"),
    ("shortcuts", "lazyground.motion.shortcut", "_random_shortcuts"),
    ("relax", "lazyground.motion.shortcut", "_relax"),
    ("fine", "lazyground.motion.shortcut", "_FineCheck.first_failure"),
    ("toppra", "lazyground.motion.trajectory", "_time_curve"),
    ("dense", "lazyground.motion.trajectory", "first_colliding_join"),
    ("limits", "lazyground.motion.pipeline", "world_limits"),
    ("limits", "lazyground.motion.limits", "world_limits"),
]


# ------------------------------------------------------------------------------------------------ worker
def _worker(scene_name: str) -> None:
    sys.path.insert(0, os.getcwd())  # this tree's lazyground first
    out = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # anything printed goes to stderr, the protocol alone to the pipe
    import importlib
    from dataclasses import replace
    from types import SimpleNamespace

    import numpy as np

    from lazyground import api
    from lazyground.drake.world import DrakeWorld
    from lazyground.motion import pipeline
    from lazyground.motion.validate import trajectory_problems
    from lazyground.planning import path_is_valid
    from lazyground.scene import load_scene

    spent: dict[str, float] = {}

    def timed(label, fn):
        def wrapper(*args, **kwargs):
            t0 = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent[label] = spent.get(label, 0.0) + time.process_time() - t0
        return wrapper

    present = set()
    for label, module, attr in PHASES:
        mod = importlib.import_module(module)
        owner, name = (getattr(mod, attr.split(".")[0]), attr.split(".")[1]) if "." in attr else (mod, attr)
        if hasattr(owner, name) and not getattr(getattr(owner, name), "_timed", False):
            wrapped = timed(label, getattr(owner, name))
            wrapped._timed = True
            setattr(owner, name, wrapped)
            present.add(label)

    captured = {}
    make_motion = pipeline.make_motion

    def capture(space, checker, result, settings, limits, rng, *args, **kwargs):
        captured.update(result=result, settings=settings, state=rng.bit_generator.state)
        return make_motion(space, checker, result, settings, limits, rng, *args, **kwargs)

    pipeline.make_motion = capture

    def recheck(result) -> list[int]:
        """Failed re-checks at the tests' resolution and half of it: the path's + the trajectory's (0-2 each)."""
        planner = getattr(captured["settings"], "planner", captured["settings"])  # a PlannerSettings in 703386a
        fine = planner.resolution / planner.validation_factor
        raw = result["traj"]
        traj = None if raw is None else SimpleNamespace(t=raw["t"], q=raw["q"], qd=raw["qd"], qdd=raw["qdd"], limits=SimpleNamespace(
            velocity=raw["velocity"], acceleration=raw["acceleration"]))
        bad = []
        for res in (fine, fine / 2):
            bad.append(int(path_is_valid(world.space, world, result["path"], res) != -1)
                       + int(traj is None or bool(trajectory_problems(traj, world.space, world, world.start,
                                                                       result["goal"], res))))
        return bad
    scene = load_scene(f"yaml_scenes/{scene_name}.yaml")
    world = DrakeWorld(scene, visual=False)
    request = SCENES[scene_name]
    api.plan(scene, request, seed=100, world=world)  # warm: kernels loaded, caches filled
    template = captured["result"]
    pickle.dump(("ready", sorted(present)), out)
    out.flush()
    stdin = sys.stdin.buffer
    while True:
        try:
            cmd, arg = pickle.load(stdin)
        except EOFError:
            return
        if cmd == "check":  # another tree's result, re-checked by this tree's code
            reply = recheck(arg)
        elif cmd == "capture":
            captured.clear()
            report = api.plan(scene, request, seed=arg, world=world)
            res = captured.get("result")
            reply = None if res is None or res.path is None else dict(
                path=np.array(res.path), final=None if res.goal is None else res.goal.final, state=captured["state"])
        else:  # replay
            goal = replace(template.goal, final=arg["final"]) if template.goal is not None else None
            result = replace(template, path=arg["path"], goal=goal)
            rng = np.random.default_rng()
            rng.bit_generator.state = arg["state"]
            settings = captured["settings"]
            spent.clear()
            checks0, check_s0 = world.checks, world.check_time
            t0, c0 = time.perf_counter(), time.process_time()
            shortened, motion = pipeline.motion_for_world(world, result, settings, rng)
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            checks, collision = world.checks - checks0, world.check_time - check_s0
            traj = motion.trajectory
            out_arrays = dict(path=np.array(shortened.path), goal=np.array(arg["path"][-1]), traj=None if traj is None else
                              dict(t=traj.t, q=traj.q, qd=traj.qd, qdd=traj.qdd, velocity=traj.limits.velocity,
                                   acceleration=traj.limits.acceleration))
            reply = dict(wall=wall, cpu=cpu, phases=dict(spent), checks=checks, collision=collision,
                         length=float(motion.shortcut.length), raw=float(motion.raw_length), bad=recheck(out_arrays),
                         duration=float(traj.duration) if traj is not None else float("nan"), result=out_arrays)
        pickle.dump(reply, out)
        out.flush()


# ------------------------------------------------------------------------------------------------ driver
class _Tree:
    def __init__(self, label: str, root: str, scene: str):
        self.label = label
        self.proc = subprocess.Popen(["nice", "-n", "0", sys.executable, os.path.abspath(__file__), "--worker", scene],
                                     cwd=root, stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        status, self.phases = self.read()
        assert status == "ready"

    def ask(self, cmd: str, arg):
        pickle.dump((cmd, arg), self.proc.stdin)
        self.proc.stdin.flush()
        return self.read()

    def read(self):
        return pickle.load(self.proc.stdout)

    def close(self):
        self.proc.stdin.close()
        self.proc.wait()


def _median(values):
    import numpy as np

    values = [v for v in values if v is not None]
    return float(np.median(values)) if values else float("nan")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--tree", action="append", required=True, help="LABEL=PATH of a lazyground checkout")
    parser.add_argument("--scenes", nargs="+", default=list(SCENES))
    parser.add_argument("--seeds", type=int, default=20)
    args = parser.parse_args(argv)
    trees = [t.split("=", 1) for t in args.tree]
    labels = [label for label, _ in trees]
    phase_names = list(dict.fromkeys(label for label, _, _ in PHASES))
    print(f"# motion step per request, median ms over seeds 0-{args.seeds - 1} (same raw paths for every tree, "
          f"trees interleaved); load {os.getloadavg()[0]:.1f} at start")
    header = ["scene", "tree", "motion", "cpu", *phase_names, "collision", "checks", "length", "duration", "bad", "bad/2",
              f"bad ({labels[0]}'s check)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for scene in args.scenes:
        workers = [_Tree(label, root, scene) for label, root in trees]
        inputs = [workers[0].ask("capture", seed) for seed in range(args.seeds)]
        rows = {label: [] for label in labels}
        for k, payload in enumerate(inputs):
            if payload is None:
                continue
            order = workers if k % 2 == 0 else workers[::-1]
            for w in order:
                rows[w.label].append(w.ask("replay", payload))
            for w in workers:  # every tree's result re-checked by the first tree's code too (independent of the others)
                row = rows[w.label][-1]
                row["bad_first"] = row["bad"] if w is workers[0] else workers[0].ask("check", row.pop("result"))
                row.pop("result", None)
        for w in workers:
            got = rows[w.label]
            cells = [scene, w.label, f"{_median([r['wall'] for r in got]) * 1e3:.1f}",
                     f"{_median([r['cpu'] for r in got]) * 1e3:.1f}"]
            for name in phase_names:
                cells.append(f"{_median([r['phases'].get(name, 0.0) for r in got]) * 1e3:.1f}" if name in w.phases else "-")
            cells += [f"{_median([r['collision'] for r in got]) * 1e3:.1f}", f"{_median([r['checks'] for r in got]):.0f}",
                      f"{_median([r['length'] for r in got]):.3f}", f"{_median([r['duration'] for r in got]):.2f}",
                      f"{sum(r['bad'][0] for r in got)}/{len(got)}",
                      f"{sum(r['bad'][1] for r in got)}/{len(got)}",
                      f"{sum(r['bad_first'][0] for r in got)}/{len(got)}"]
            print("| " + " | ".join(cells) + " |", flush=True)
            w.close()
        for first in labels[:-1]:  # every other tree against the last
            base, other = rows[first], rows[labels[-1]]
            ratio = _median([a["wall"] / b["wall"] for a, b in zip(base, other)])
            cpu = _median([a["cpu"] / b["cpu"] for a, b in zip(base, other)])
            lengths = [b["length"] / a["length"] for a, b in zip(base, other)]
            mean_len = sum(lengths) / max(1, len(lengths))
            durations = [b["duration"] / a["duration"] for a, b in zip(base, other)
                         if a["duration"] > 0 and b["duration"] == b["duration"]]  # nan: no trajectory
            mean_dur = sum(durations) / max(1, len(durations))
            print(f"|  | {first} / {labels[-1]}, median per request | {ratio:.2f}x | {cpu:.2f}x | length "
                  f"{labels[-1]} / {first}, mean {mean_len:.4f} (max {max(lengths, default=float('nan')):.4f}) | duration, mean {mean_dur:.4f} "
                  f"(max {max(durations, default=float('nan')):.4f}) |", flush=True)
    print(f"# load {os.getloadavg()[0]:.1f} at end; phases nest (fine may run inside greedy; dense inside timing); "
          "bad, bad/2 = failed re-checks of path and trajectory at the fine resolution (the tests'), and at half of it")
    return 0


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "--worker":
        _worker(sys.argv[2])
    else:
        sys.exit(main())
