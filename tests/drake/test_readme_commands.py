"""Issue 34: every `lazyground plan` line of README.md and docs/ on a shipped scene solves what it promises.

The README's one-tree line (`fetch_boxes_3 "pick up a box" --algorithm rrt`) timed out after 31 s on a new
user's machine. Each line runs here through the CLI's own parser and the API, bounded by iterations (never by
the clock): a planner that needs more than ``BUDGET`` iterations at the line's seed does not belong in a
first-contact example.
"""

import re
import shlex
from pathlib import Path

import pytest

from lazyground import api
from lazyground.bundled import bundled_scene
from lazyground.cli import build_parser
from lazyground.cli_options import cli_values
from tests.counts import BY_COUNTS

ROOT = Path(__file__).resolve().parents[2]
BUDGET = 20_000  # iterations; the README's lines need at most a few thousand


def _plan_lines() -> list[str]:
    """Plan commands in the pages' bash blocks whose scene ships (a file in the repo or a bundled name);
    the tutorial's own scenes are tests/drake/test_tutorial.py's."""
    lines = []
    for page in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        for block in re.findall(r"```bash\n(.*?)```", page.read_text(), re.S):
            for line in block.splitlines():
                if line.startswith("lazyground plan ") and _ships(shlex.split(line, comments=True)[2]):
                    lines.append(line)
    return lines


def _ships(scene: str) -> bool:
    return (ROOT / scene).is_file() or bundled_scene(scene) is not None


LINES = _plan_lines()


def test_the_readme_has_plan_lines():
    assert len(LINES) >= 9


@pytest.mark.parametrize("line", LINES, ids=[f"line{i}" for i in range(len(LINES))])
def test_readme_plan_line_solves(line):
    args = build_parser().parse_args(shlex.split(line, comments=True)[1:])
    overrides = {k: v for k, v in cli_values(args).items() if v is not None and k not in BY_COUNTS}
    scene = ROOT / args.scene if (ROOT / args.scene).is_file() else args.scene
    report = api.plan(scene, args.request, **{**BY_COUNTS, "max_iterations": BUDGET, **overrides})
    assert report.result.solved, f"{line}: {report.result.status.value}: {report.result.message}"
