#!/bin/sh
# The figures of issue 32's "suite in under 8 minutes on 2 cores": wall time of the whole suite serial and with
# pytest-xdist's two workers (the README's test command, -n 2), then two workers beside two busy loops (the suite
# must still pass), each with the 40 slowest tests. Run from the repository root on a quiet machine: about
# 9 + 5 + 10 minutes.
#   sh tools/suite_time.sh [OUT_DIR]        (default /tmp/lazyground-suite-time; one log per run there)
set -u
out=${1:-/tmp/lazyground-suite-time}
mkdir -p "$out"

run() {  # name, pytest arguments...
    name=$1
    shift
    start=$(date +%s)
    python3 -m pytest -q -p no:cacheprovider --durations=40 "$@" > "$out/$name.log" 2>&1
    status=$?
    echo "$name: exit $status, $(( $(date +%s) - start )) s wall ($(tail -n 1 "$out/$name.log"))"
}

run serial
run xdist-2 -n 2
yes > /dev/null &
busy1=$!
yes > /dev/null &
busy2=$!
run xdist-2-beside-2-busy-loops -n 2
kill "$busy1" "$busy2"
