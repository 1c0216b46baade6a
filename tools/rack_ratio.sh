#!/bin/bash
# Issue #33, the racks' target (N = 64 at most 3x N = 4): N = 4 and N = 64 alternated in chunks of 5 layouts, the order
# flipped each chunk, one process at a time (the host's speed swings between phases; both sizes see each phase).
# Usage (repository root): bash tools/rack_ratio.sh ROBOT OUTDIR   -> OUTDIR/rack_ROBOT_{4,64}.jsonl and two summary lines
set -e
robot=$1; out=${2:-/tmp/rack_ratio}
mkdir -p "$out"; rm -f "$out/rack_${robot}_4.jsonl" "$out/rack_${robot}_64.jsonl"
i=0
for ch in 0-4 5-9 10-14 15-19; do
  if (( i % 2 == 0 )); then order="4 64"; else order="64 4"; fi
  for n in $order; do
    PYTHONPATH=. python3 tools/rack_targets.py "$robot" "$n" "$ch" --no-nf --strategies cover --jsonl "$out/rack_${robot}_$n.jsonl" > /dev/null
  done
  i=$((i+1))
done
for n in 4 64; do echo -n "$robot N=$n: "; PYTHONPATH=. python3 tools/rack_targets.py summary "$out/rack_${robot}_$n.jsonl" | tail -1; done
