"""CPU seconds of the first and second grounding in a fresh process (issue 32: the parser's one-time cost).

    python3 tools/first_request_time.py [--runs 4] [--cold]

Each run is a new Python process: scene loaded, then ``process_time`` around the first ``grounding.ground``
(lexicon, object types, the lark parser: cached per user) and a second one. ``--cold`` empties the grammar
cache first (what a fresh install pays once).
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
CHILD = """
import time, grounding
from lazyground.scene import load_scene
scene = load_scene("parking_1")
t0 = time.process_time(); grounding.ground("park", scene)
t1 = time.process_time(); grounding.ground("park in row t", scene)
print(f"{t1 - t0:.4f} {time.process_time() - t1:.4f}")
"""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=4)
    parser.add_argument("--cold", action="store_true", help="empty the grammar cache before each run")
    args = parser.parse_args()
    sys.path.insert(0, str(REPO))
    from lazyground.user_cache import cache_dir

    for i in range(args.runs):
        if args.cold:
            shutil.rmtree(cache_dir("grammar"), ignore_errors=True)
        out = subprocess.run([sys.executable, "-c", CHILD], cwd=REPO, capture_output=True, text=True, check=True)
        first, second = out.stdout.split()
        print(f"run {i}: first grounding {float(first):.3f} s CPU, second {float(second):.4f} s CPU")
    return 0


if __name__ == "__main__":
    sys.exit(main())
