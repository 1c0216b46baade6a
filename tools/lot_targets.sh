#!/bin/sh
# The lot targets of issue #33 in one command (benchmarks/RESULTS.md, "Lots against the baselines, censoring
# accounted for"): on the fixed-layout lot (lot:N:2:0:576) at N = 64 and 256,
#   1. cover-connect and round-robin (consecutive), RUNS seeds, 20 s each: Mann-Whitney p per size;
#   2. the baselines nearest-first (10 s a planner call) and eager, BASELINE_RUNS seeds, 60 s each, into the same
#      results.csv (--resume skips step 1's runs): each baseline's median over cover-connect's, as a lower bound
#      where the baseline's unsolved runs censor its median;
#   3. tools/lot_baselines.py: nearest-first's rank of the reachable spot (its time >= (rank - 1) x 10 s), eager's
#      up-front phase alone, and eager's search against the same up-front phase + cover-connect.
# Usage: tools/lot_targets.sh [OUT] [RUNS] [BASELINE_RUNS]    (defaults: bench_lot_targets 20 10)
# Quiet 2-core machine, --jobs 2: about 30-35 min (estimated from a loaded run; see RESULTS.md).
set -e
OUT=${1:-bench_lot_targets}
RUNS=${2:-20}
BASELINE_RUNS=${3:-10}
COMMON="--family-sweep lot-fixed --sizes 64,256 --algorithms bidirectional --strategies consecutive,cover-connect --time-limit 20 --jobs 2 --out $OUT"
nice python3 -m lazyground bench $COMMON --runs "$RUNS" > /dev/null
nice python3 -m lazyground bench $COMMON --runs "$BASELINE_RUNS" --resume --baselines nearest-first,eager --baseline-time-limit 60 > /dev/null
PYTHONPATH=. nice python3 tools/lot_baselines.py --sizes 64,256,512 --upfront-seeds 5 --alone-seeds 10 --search-seeds 5 \
    --time-limit 30 > "$OUT/baseline_parts.md"
echo "wrote $OUT/table.md (sections 'Each method against round-robin per size' and 'Baselines against ours per size'),"
echo "$OUT/family_sweep.png and $OUT/baseline_parts.md"
