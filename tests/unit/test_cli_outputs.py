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
    ([LOT, "park", "--speed", "0"], "error: --speed must be in [0.01, 1], got 0"),
    # audit8: these ran out of memory after planning ("internal error: MemoryError: Unable to allocate 238. GiB")
    ([LOT, "park", "--speed", "1e-6"], "error: --speed must be in [0.01, 1], got 1e-06"),
    ([LOT, "park", "--sample-rate", "1e9"], "error: --sample-rate must be in (0, 1000], got 1e+09"),
    # audit8: these wrote the wrong kind of file (--html x.png, --ros-trajectory t.csv, --plot out: out.png while
    # saying "wrote out") or failed with an internal error (exit 3) after planning
    ([LOT, "park", "--html", "{tmp}/x.png"], "error: --html {tmp}/x.png: unknown suffix '.png'; --html writes .html, .htm"),
    ([LOT, "park", "--ros-trajectory", "{tmp}/t.csv"], "error: --ros-trajectory {tmp}/t.csv: unknown suffix '.csv'; --ros-trajectory writes .yaml"),
    ([LOT, "park", "--plot", "{tmp}/out"], "error: --plot {tmp}/out: no suffix; --plot writes "),
    ([LOT, "park", "--plot", "{tmp}/out.txt"], "error: --plot {tmp}/out.txt: unknown suffix '.txt'"),
    ([LOT, "park", "--animate", "{tmp}/out.bmp"], "error: --animate {tmp}/out.bmp: unknown suffix '.bmp'; --animate writes "),
    ([LOT, "park", "--html", "/proc/lazyground.html"], "error: --html /proc/lazyground.html: cannot write: "),
])
def test_bad_outputs_fail_before_planning(argv, message, tmp_path, capsys):
    assert refused(["plan", *argv], message, tmp_path, capsys) == ""  # nothing planned: the plan summary goes to stdout


def refused(argv: list[str], message: str, tmp_path, capsys) -> str:
    """``main(argv)`` ("{tmp}" standing for ``tmp_path``) exits 2 with one stderr line starting with ``message``;
    returns what it printed on stdout."""
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert err.splitlines() == [err.strip()] and err.startswith(message.replace("{tmp}", str(tmp_path))), err
    return out


def test_the_write_check_leaves_no_file_behind(tmp_path):
    from lazyground.outputs import output_problem
    from lazyground.scene import load_scene

    assert output_problem(load_scene(LOT), html=str(tmp_path / "x.html"), plot=str(tmp_path / "x.png")) is None
    assert list(tmp_path.iterdir()) == []


def test_an_output_that_fails_while_written_is_bad_input():
    # audit8: a full disk (--html /dev/full) was "internal error: OSError: [Errno 28] ...", exit 3
    from lazyground.cli import UsageError, _writing

    def full():
        raise OSError(28, "No space left on device")

    with pytest.raises(UsageError, match=r"^--html out.html: cannot write: No space left on device$"):
        _writing("--html out.html", full)
