"""Issue #33: the approach-clearance flags (lazyground.drake.approach) per can kind on arm racks, and their CPU cost.

Usage (from the repository root): PYTHONPATH=. python3 tools/approach_flags.py ROBOT N LAYOUTS (e.g. panda 64 0,1,12)
Prints per layout: the flags' CPU s, (kind, flagged) counts over the regions the reach prior keeps, the reachable can's regions.
"""
import sys, time
from lazyground.bench.families import generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.bench.runner import load_problem
from lazyground.goals import reach_prior_drops
from lazyground.drake.approach import blocked_approaches
robot, n = sys.argv[1], int(sys.argv[2])
for lay in [int(x) for x in sys.argv[3].split(",")]:
    key = f"rack:{robot}:{n}:1:{lay}"
    kinds = can_kinds(generate(parse_key(key)))
    p = load_problem(key); regions, _ = p.ground(); w = p.world
    drops = reach_prior_drops(regions, w)
    t = time.process_time(); fl = blocked_approaches(w, tuple(regions), drops); t = time.process_time() - t
    from collections import Counter
    c = Counter((kinds[r.id.split('/')[0]], j in fl) for j, r in enumerate(regions) if j not in drops)
    reach = [(r.id, j in fl) for j, r in enumerate(regions) if j not in drops and kinds[r.id.split('/')[0]] == 'reachable']
    print(key, f"{t:.3f}s", dict(c), reach, flush=True)
