"""Issue #33, arm racks: where a request's planning time goes at a given N, median over layouts (CPU seconds).

Each layout is a fresh world (as in tools/rack_targets.py); one untimed plan on another layout first compiles the
kernels. Per request: grounding, making the goal source (the reach prior's drops, the IK region table), IK draws (the
goal sampling less that making), collision checks in the search, the loop's rest; iterations, IK attempts, checks
and µs per check (the search's collision seconds over its checks).

Usage (from the repository root):  PYTHONPATH=. python3 tools/rack_split.py ROBOT N [LAYOUTS]   (default 20 layouts)
"""

from __future__ import annotations

import sys
import time

import numpy as np

import lazyground.planning.stop as stop_module
from lazyground import api
from lazyground.bench.runner import load_problem
from lazyground.settings import Algorithm, Strategy
from lazyground.tasks import reach


def main(argv: list[str]) -> int:
    robot, n = argv[0], int(argv[1])
    layouts = range(int(argv[2]) if len(argv) > 2 else 20)
    stop_module.CLOCK = time.process_time
    made: list[float] = []
    make = reach.make_goal_source

    def timed(*args, **kwargs):
        t0 = time.process_time()
        out = make(*args, **kwargs)
        made.append(time.process_time() - t0)
        return out

    reach.make_goal_source = timed
    warm = load_problem(f"rack:{robot}:{n}:1:{max(layouts) + 1}")
    api.plan(warm.scene, warm.request, seed=0, world=warm.world, strategy=Strategy.COVER.value, algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=30)
    rows = []
    for lay in layouts:
        p = load_problem(f"rack:{robot}:{n}:1:{lay}")
        made.clear()
        rep = api.plan(p.scene, p.request, seed=0, world=p.world, strategy=Strategy.COVER.value, algorithm=Algorithm.BIDIRECTIONAL.value, time_limit=30)
        r, source = rep.result, sum(made)
        rows.append((rep.grounding_s + r.time_s, rep.grounding_s, source, r.goal_sampling_s - source, r.collision_s,
                     r.time_s - r.goal_sampling_s - r.collision_s, r.iterations,
                     sum(st.attempts for st in r.region_stats), r.collision_checks))
    a = np.array(rows)
    med = np.median(a, axis=0)
    print(f"{robot} N={n}, {len(rows)} layouts, medians: planning {med[0]:.3f} s = grounding {med[1]:.3f}, goal source "
          f"{med[2]:.3f}, IK draws {med[3]:.3f}, collision {med[4]:.3f}, rest {med[5]:.3f}; iterations {med[6]:.0f}, "
          f"IK attempts {med[7]:.0f}, checks {med[8]:.0f}, {1e6 * a[:, 4].sum() / max(a[:, 8].sum(), 1):.2f} µs a check")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
