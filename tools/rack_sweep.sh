#!/bin/sh
# Issue #33, arm racks: time to the first solution against N for the Panda and the Fetch (1 reachable can among N),
# our strategies on the two-tree planner against ground-then-plan nearest-first (10 s a candidate, CALL_BUDGET in
# lazyground/bench/baselines.py) and eager all-goal IK. Writes OUT/table.md (the sweep table and the Mann-Whitney
# tests against consecutive = round-robin), OUT/family_sweep.png and OUT/results.csv.
# Usage: tools/rack_sweep.sh [OUT] [RUNS]   (run from the repository root; ~35-50 min on a quiet 2-core machine)
set -e
OUT=${1:-bench_output/racks}
RUNS=${2:-10}
python3 -m lazyground bench --family-sweep rack-panda,rack-fetch --sizes 1,4,16,64 --algorithms bidirectional \
    --strategies cover,reward-penalty,consecutive --baselines nearest-first,eager \
    --runs "$RUNS" --time-limit 60 --jobs 2 --out "$OUT"
