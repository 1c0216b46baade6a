"""Our own held-out-style paraphrase list (tests/corpus/paraphrases.yaml): the share grounded exactly as meant.

Run: ``python3 -m tools.paraphrases [--show]``.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

LIST = ROOT / "tests" / "corpus" / "paraphrases.yaml"


def check() -> list[tuple[str, str, set, object]]:
    """(scene, text, expected, got: a set of ids or the error line) per paraphrase."""
    from grounding import GroundingError, ground
    from lazyground.scene import load_scene

    out = []
    scenes: dict = {}
    for name, text, want in yaml.safe_load(LIST.read_text()):
        sc = scenes.setdefault(name, load_scene(ROOT / "yaml_scenes" / f"{name}.yaml"))
        try:
            got = {i.id for i in ground(text, sc).interpretations}
        except GroundingError as exc:
            got = str(exc)
            unfit = set(re.findall(r"(\S+) cannot be grasped", got))
            if unfit and unfit == {w.split(":")[1] for w in want}:  # understood; too big for the gripper
                got = set(want)
        out.append((name, text, set(want), got))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--show", action="store_true", help="print the misses")
    args = ap.parse_args(argv)
    rows = check()
    right = [r for r in rows if r[3] == r[2]]
    print(f"paraphrases grounded as meant: {len(right)} of {len(rows)} ({100 * len(right) / len(rows):.0f}%)")
    if args.show:
        for name, text, want, got in rows:
            if got != want:
                print(f"  [{name}] {text!r}: meant {sorted(want)}, got {sorted(got) if isinstance(got, set) else got}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
