#!/bin/sh
# Issue #33, arm racks: time to the first solution against N for the Panda and the Fetch (1 reachable can among N),
# our strategies on the two-tree planner against ground-then-plan nearest-first (10 s a candidate, CALL_BUDGET in
# lazyground/bench/baselines.py) and eager all-goal IK. Each size runs RUNS rack layouts (layout seeds 0..RUNS-1, so
# the reachable can's rank in the nearest-first order varies), one planner seed each. Writes OUT/table.md (the sweep
# table, and the Mann-Whitney tests against consecutive = round-robin, per layout), OUT/family_sweep.png, results.csv.
# Usage: tools/rack_sweep.sh [OUT] [RUNS] [SIZES]   (from the repository root)
# Environment: LIMIT (ours, default 30 s), BASELINE_LIMIT (the baselines', default 150 s: nearest-first spends its
# 10 s on every valid-but-unreachable can nearer than the reachable one, up to 137 s on a 64-can Panda rack, so a
# 30 s limit would cut it off and cap the ratio), STRATEGIES (default cover,consecutive), BASELINES (default
# nearest-first; eager's unsolved runs last the whole limit: run it apart, BASELINES=eager BASELINE_LIMIT=60).
# Duration quiet, by estimate from CPU-clock runs (tools/rack_targets.py): RUNS=20 SIZES=64 ~25 min for both robots.
set -e
OUT=${1:-bench_output/racks}
RUNS=${2:-10}
SIZES=${3:-1 4 16 64}
SCENES=""
for robot in panda fetch; do
  for n in $SIZES; do
    s=0
    while [ "$s" -lt "$RUNS" ]; do SCENES="$SCENES,rack:$robot:$n:1:$s"; s=$((s + 1)); done
  done
done
python3 -m lazyground bench --scenes "${SCENES#,}" --algorithms bidirectional \
    --strategies "${STRATEGIES:-cover,consecutive}" --baselines "${BASELINES:-nearest-first}" \
    --runs 1 --time-limit "${LIMIT:-30}" --baseline-time-limit "${BASELINE_LIMIT:-150}" --jobs 2 --out "$OUT"
