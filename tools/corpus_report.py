"""Plan every MoveIt corpus scene with default settings over seeds; print a table per scene (#15).

    PYTHONPATH=$PWD python3 tools/corpus_report.py --seeds 10            # 30 s limit (the robot's default)
    PYTHONPATH=$PWD python3 tools/corpus_report.py --seeds 3 --only bookshelf_cans

Times are grounding + planning per run (the world is built once per scene; its set-up is a column).
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from lazyground.bench.moveit_corpus import corpus_entries, run_entry, table


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=10, help="seeds 0..N-1 per scene")
    parser.add_argument("--only", action="append", help="scene names (repeatable; default: all)")
    args = parser.parse_args(argv)
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        for entry in corpus_entries():
            if args.only and entry.name not in args.only:
                continue
            mine, _ = run_entry(entry, Path(tmp), range(args.seeds))
            runs += mine
            print(f"{entry.name}: {sum(r.status == 'solved' for r in mine)}/{len(mine)} solved", file=sys.stderr, flush=True)
    print("\n".join(table(runs)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
