"""Issue #33: per-region IK outcome counts of a rack (every region tried PER times, round-robin), written to OUT.json,
for tools/rack_allocation_sim.py. Usage: PYTHONPATH=. python3 tools/rack_outcomes.py rack:panda:64:1:0 PER OUT.json"""
import sys, json, time
import numpy as np
from lazyground.bench.families import load_family_scene, generate, parse_key
from lazyground.bench.families.rack import can_kinds
from lazyground.drake.world import DrakeWorld
from lazyground.drake.ik.source import IKGoalSource
from lazyground.planning.stop import StopCondition
import grounding
key = sys.argv[1]; per = int(sys.argv[2])
scene = load_family_scene(key); kinds = can_kinds(generate(parse_key(key)))
world = DrakeWorld(scene, visual=False)
regions = grounding.ground("pick up a can", scene).goal_regions
src = IKGoalSource(regions, world, give_up_after=10**6)
rng = np.random.default_rng(0); t = time.time()
while src.total_attempts < per * len(regions):
    src.draw(20, rng, StopCondition.after(None))
out = [dict(kind=kinds[r.object], obj=r.object, attempts=st.attempts, valid=st.valid, failures=st.failures) for r, st in zip(regions, src.stats)]
json.dump(out, open(sys.argv[3], "w"))
print(key, len(regions), time.time() - t)
