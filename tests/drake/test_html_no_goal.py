"""#20: ``--html`` with the two-tree planner and no reachable goal is a planning failure (exit 1), not exit 3."""

from __future__ import annotations

import pytest

pytest.importorskip("pydrake")

from lazyground.cli import main  # noqa: E402
from tests.unit.test_grounding import REPO  # noqa: E402

NEAR = "pose: {xyz: [0.65, -0.185, 0.73]}"
FAR = "pose: {xyz: [2.5, -0.185, 0.0575]}"  # on the floor 2.5 m away: out of the arm's reach


def test_html_with_no_valid_goal_exits_1(tmp_path, capsys):
    text = (REPO / "yaml_scenes" / "fetch_cans_1.yaml").read_text()
    line = next(ln for ln in text.splitlines() if ln.startswith("- {id: Can1,"))
    assert NEAR in line
    scene = tmp_path / "far_can.yaml"
    scene.write_text(text.replace(line, line.replace(NEAR, FAR)))
    for flags, why in (([], "proven unreachable by the reach prior"), (["--no-reach-prior"], "out of reach")):
        html = tmp_path / f"x{len(flags)}.html"
        code = main(["plan", str(scene), "pick up Can1", "--algorithm", "bidirectional", "--time-limit", "1000",
                     "--html", str(html), *flags])
        out, err = capsys.readouterr()
        assert code == 1, err
        assert "status: no_valid_goal" in out and why in out, out
        assert html.is_file() and html.stat().st_size > 1000
