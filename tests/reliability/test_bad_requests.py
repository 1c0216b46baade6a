"""Odd requests (tests/corpus/bad_requests.yaml) through the CLI: exit 2, one line, no planning.

Each entry is run as ``lazyground.cli.main(["plan", scene, request])``. The
request must be refused by grounding (or by the argument parser) before any
Drake world is built or the planner is started: ``grounding.ground`` is
wrapped to record what it did and ``lazyground.tasks.run`` is replaced by a
function that fails the test.
"""

from __future__ import annotations

import pytest
import yaml

import grounding
from grounding.model import GroundingError
from lazyground import api, cli
from tests.reliability.conftest import CORPUS, HAS_DRAKE, scene_path

SCENE_FILES = {
    "parking": scene_path("parking_1"),
    "fetch": scene_path("fetch_put_box_on_table"),
    "kitchen": scene_path("kitchen_put_cup_on_table"),
}
CASES = yaml.safe_load((CORPUS / "bad_requests.yaml").read_text(encoding="utf-8"))


def request_text(case: dict) -> str:
    """The entry's request; long ones are generated here rather than stored."""
    if "repeat" in case:
        unit, length = case["repeat"], case["length"]
        return (unit * (length // len(unit) + 1))[:length]
    return case["request"]


def test_corpus_shape():
    assert len(CASES) >= 50
    names = [c["name"] for c in CASES]
    assert len(set(names)) == len(names)
    for c in CASES:
        assert c["scene"] in SCENE_FILES and c.get("class", "GroundingError") in ("GroundingError", "UsageError"), c
        assert ("request" in c) != ("repeat" in c) and c["error"], c
    assert {c["scene"] for c in CASES} >= {"parking", "fetch"}
    assert max(len(request_text(c)) for c in CASES) >= 10_000


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_bad_request(case, monkeypatch, capsys):
    text = request_text(case)
    scene = str(SCENE_FILES[case["scene"]])
    outcomes: list = []
    real_ground = grounding.ground

    def recording_ground(request, scene_, *args, **kwargs):
        try:
            g = real_ground(request, scene_, *args, **kwargs)
        except Exception as exc:
            outcomes.append(exc)
            raise
        outcomes.append(g)
        return g

    def no_planning(*args, **kwargs):
        raise AssertionError("planning started for a request that should have been refused")

    monkeypatch.setattr(grounding, "ground", recording_ground)
    monkeypatch.setattr(api.tasks, "run", no_planning)  # every task starts here
    monkeypatch.setattr(api, "make_goal_source", no_planning)
    if HAS_DRAKE:  # refused before any Drake work: the refusal is cheap (asserted by what runs, not by the clock)
        monkeypatch.setattr("lazyground.drake.world.DrakeWorld", no_planning)
    code = cli.main(["plan", scene, text])
    captured = capsys.readouterr()
    err = captured.err.splitlines()
    assert code == cli.EXIT_BAD_INPUT, (code, captured.err)
    assert len(err) == 1 and err[0].startswith("error: "), captured.err
    assert "Traceback" not in captured.err and captured.out == ""
    assert case["error"] in err[0], err[0]
    if case.get("class", "GroundingError") == "GroundingError":
        assert len(outcomes) == 1 and isinstance(outcomes[0], GroundingError), outcomes
    else:
        assert outcomes == []  # refused by the argument parser, before grounding
