"""When Drake's batch checks may run on several threads (OpenMP) without hanging a forked process.

Drake parallelises ``CheckConfigsCollisionFree`` with OpenMP over its pool of
contexts. GNU OpenMP's thread pool does not survive ``fork()``: a process forked
from one that has used the pool hangs in its first parallel region (#19, seen in
bench workers). So batches go parallel only when they are large enough to pay
for the threads (:data:`PARALLEL_MIN_BATCH`), and never in a process forked after
its parent used the pool (an ``os.register_at_fork`` hook notices): that process
checks serially, slower but never stuck. ``lazyground bench`` forks its workers from a
process that has not checked anything, so they run parallel batches; pytest's
workers, forked from a process that has, run serial ones (and keep the test
process's settings, which a ``spawn``-ed worker would not).
"""

from __future__ import annotations

import os

# Configurations per batch from which Drake's parallel check is used. Below it the
# threads' start-up and hand-over cost more than they save: on a loaded machine a parallel
# batch of 10-64 configurations was 9-46x slower than a serial one, from ~256 about even
# (benchmarks/RESULTS.md, #19). On a quiet machine a large batch was reported ~2x faster (not re-measured).
PARALLEL_MIN_BATCH = 512

_used = False  # this process has run a parallel batch (its OpenMP pool exists)
_broken = False  # this process was forked after its parent used the pool: serial only


def _after_fork_in_child() -> None:
    global _broken
    _broken = _broken or _used


os.register_at_fork(after_in_child=_after_fork_in_child)


def parallel_batch(n: int) -> bool:
    """Whether a batch of ``n`` configurations should be checked on several threads (and mark the pool used)."""
    global _used
    if n < PARALLEL_MIN_BATCH or _broken or os.cpu_count() == 1:
        return False
    _used = True
    return True

