"""#20: output options are checked before planning (exit 2 at once, nothing planned)."""

from __future__ import annotations

import pytest

from lazyground.cli import main
from tests.unit.test_grounding import REPO

FETCH = str(REPO / "yaml_scenes" / "fetch_cans_1.yaml")
LOT = str(REPO / "yaml_scenes" / "parking_1.yaml")


@pytest.mark.parametrize("argv,message", [
    ([FETCH, "pick up a can", "--plot", "out.png"], "error: --plot: top-down parking plots need a planar robot"),
    ([FETCH, "pick up a can", "--animate", "out.gif"], "error: --animate: top-down parking plots need a planar robot"),
    ([LOT, "park", "--html", "/no/such/folder/x.html"], "error: --html /no/such/folder/x.html: folder /no/such/folder does not exist"),
    ([LOT, "park", "--plot", "{tmp}"], "error: --plot {tmp}: is a folder"),
    ([LOT, "park", "--trajectory", "/no/such/folder/t.csv"], "error: --trajectory /no/such/folder/t.csv: folder /no/such/folder does not exist"),
    ([LOT, "park", "--ros-trajectory", "{tmp}"], "error: --ros-trajectory {tmp}: is a folder"),
    ([LOT, "park", "--speed", "0"], "error: --speed must be in (0, 1], got 0"),
])
def test_bad_outputs_fail_before_planning(argv, message, tmp_path, capsys):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["plan", *argv]) == 2
    out, err = capsys.readouterr()
    assert out == ""  # nothing planned: the plan summary goes to stdout
    assert len(err.strip().splitlines()) == 1 and err.startswith(message.replace("{tmp}", str(tmp_path))), err
