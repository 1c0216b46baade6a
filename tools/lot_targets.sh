#!/bin/sh
# The lot targets of issue #33 in one command (benchmarks/RESULTS.md, "Lots against the baselines, censoring
# accounted for"): on the fixed-layout lot (lot:N:2:0:576) at N = 64 and 256,
#   1. cover-connect and round-robin (consecutive), RUNS seeds, 20 s each: Mann-Whitney p per size;
#   2. the baselines nearest-first (10 s a planner call) and eager, BASELINE_RUNS seeds, 60 s each, into the same
#      results.csv (--resume skips step 1's runs): each baseline's median over cover-connect's, as a lower bound
#      where the baseline's unsolved runs censor its median;
#   3. cover-connect against eager, both 60 s, BASELINE_RUNS seeds, interleaved in one run (OUT/eager):
#      the ratio to eager without round-robin's 20 s limit in the way;
#   4. tools/lot_baselines.py: nearest-first's rank of the reachable spot (its time >= (rank - 1) x 10 s), eager's
#      up-front phase alone, and eager's search against the same up-front phase + cover-connect.
# Usage (from the repository root): tools/lot_targets.sh [OUT] [RUNS] [BASELINE_RUNS]    (defaults: bench_lot_targets 20 10)
# Quiet 2-core machine, --jobs 2: about 50 min (estimated from loaded runs; see RESULTS.md).
set -e
OUT=${1:-bench_lot_targets}
RUNS=${2:-20}
BASELINE_RUNS=${3:-10}
mkdir -p "$OUT/eager"
COMMON="--family-sweep lot-fixed --sizes 64,256 --algorithms bidirectional --strategies consecutive,cover-connect --time-limit 20 --jobs 2 --out $OUT"
nice python3 -m lazyground bench $COMMON --runs "$RUNS" > /dev/null
nice python3 -m lazyground bench $COMMON --runs "$BASELINE_RUNS" --resume --baselines nearest-first,eager --baseline-time-limit 60 > /dev/null
nice python3 -m lazyground bench --family-sweep lot-fixed --sizes 64,256 --algorithms bidirectional --strategies cover-connect \
    --baselines eager --runs "$BASELINE_RUNS" --time-limit 60 --jobs 2 --out "$OUT/eager" > /dev/null
PYTHONPATH=. nice python3 tools/lot_baselines.py --sizes 64,256,512 --upfront-seeds 5 --alone-seeds 10 --search-seeds 5 \
    --time-limit 30 > "$OUT/baseline_parts.md"
echo "wrote $OUT/table.md (sections 'Each method against round-robin per size' and 'Baselines against ours per size'),"
echo "$OUT/eager/table.md ('Baselines against ours per size'), $OUT/family_sweep.png and $OUT/baseline_parts.md"
