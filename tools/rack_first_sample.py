"""Issue #33: IK attempts the goal source alone (no planner) makes, round-robin as the planners draw, before the
reachable can of a rack gets its first valid sample; counted, so independent of the machine's load.
Usage (from the repository root): PYTHONPATH=. python3 tools/rack_first_sample.py rack:panda:64:1:0 SEEDS DEFER
(DEFER 1: no deferral of regions whose targets all fail the screen; 8: the default, lazyground.goals.DEFER)."""
import numpy as np
import lazyground.goals as G
from lazyground.bench.families import load_family_scene, generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.drake.world import DrakeWorld
from lazyground.drake.ik.source import IKGoalSource
from lazyground.planning.stop import StopCondition
import grounding
key = sys.argv[1]; seeds = range(int(sys.argv[2])); G.DEFER = int(sys.argv[3])
scene = load_family_scene(key); kinds = can_kinds(generate(parse_key(key)))
world = DrakeWorld(scene, visual=False)
regions = grounding.ground("pick up a can", scene).goal_regions
out = []
for seed in seeds:
    src = IKGoalSource(regions, world); rng = np.random.default_rng(seed); found = None
    while found is None and not src.exhausted() and src.total_attempts < 20000:
        for s in src.draw(1, rng, StopCondition.after(None)):
            if kinds[regions[s.region].object] == "reachable":
                found = src.total_attempts
    out.append(found or 20000)
print(key, "DEFER", G.DEFER, "attempts to the reachable can's first sample", out, "median", float(np.median(out)), flush=True)
