"""#31: a report's total_s is the request as the user waits for it (api.plan's wall time less the world build),
and its split adds up to it, in the report, its JSON and its text. Every reading is on a fake clock (no outcome on
the machine's clock)."""

import pytest

pytest.importorskip("pydrake")

from lazyground import api  # noqa: E402
from lazyground.planning import stop  # noqa: E402
from lazyground.report import report_to_json, report_lines  # noqa: E402


def test_total_is_the_call_less_the_world_build_and_its_split_adds_up(monkeypatch):
    clock = stop.FakeClock(tick=1e-6)  # 1 us per reading: the 10 s limit is 10 million readings away
    monkeypatch.setattr(stop, "CLOCK", clock)
    t0 = clock()
    report = api.plan("panda_tabletop", "pick up a cup", seed=0, max_iterations=3000)
    wall = clock() - t0
    assert report.result.solved and report.setup_s > 0
    assert report.total_s is not None and report.total_s + report.setup_s <= wall
    split = report.total_split_s
    assert set(split) == {"grounding", "search", "motion", "rest"}
    assert abs(sum(split.values()) - report.total_s) < 1e-9
    assert split["search"] == report.result.time_s and all(v >= 0.0 for v in split.values()), split
    out = report_to_json(report)
    assert out["total_s"] == round(report.total_s, 6) and set(out["total_split_s"]) == set(split)
    assert any(line.startswith(f"request: {report.total_s:.3f} s (grounding") for line in report_lines(report))


@pytest.mark.parametrize("grounding_s,solved", [(0.0, True), (2.0, False)])
def test_the_time_limit_counts_the_grounding(monkeypatch, grounding_s, solved):
    # a grounding that takes 2 s of the fake clock leaves nothing of a 1 s limit: the task stops at once
    clock = stop.FakeClock(tick=1e-6)
    monkeypatch.setattr(stop, "CLOCK", clock)
    ground = api.grounding.ground

    def slow_ground(*args, **kwargs):
        out = ground(*args, **kwargs)
        clock.advance(grounding_s)
        return out

    monkeypatch.setattr(api.grounding, "ground", slow_ground)
    report = api.plan("parking_1", "park", seed=0, time_limit=1.0, max_iterations=3000)
    assert report.grounding_s >= grounding_s
    assert report.result.solved is solved, report.result.message
    if not solved:
        assert report.result.status.value == "timeout" and report.result.time_s < 0.01, report.result


def test_the_search_time_counts_making_its_goal_source(monkeypatch):
    # #33: a goal source's making (its screens, priors and flags: 0.2-0.4 s on a 64-can rack) is time the user waits
    # for; a source that takes 3 s of the fake clock to make shows in the search's time and its goal sampling
    from lazyground.tasks import reach

    clock = stop.FakeClock(tick=1e-6)
    monkeypatch.setattr(stop, "CLOCK", clock)
    make = reach.make_goal_source

    def slow_source(*args, **kwargs):
        out = make(*args, **kwargs)
        clock.advance(3.0)
        return out

    monkeypatch.setattr(reach, "make_goal_source", slow_source)
    report = api.plan("panda_tabletop", "pick up a cup", seed=0, max_iterations=3000)
    assert report.result.solved
    assert report.result.time_s >= 3.0 and report.result.goal_sampling_s >= 3.0, report.result
    assert report.total_split_s["search"] == report.result.time_s


def test_the_hand_probe_is_built_at_set_up_not_in_the_request(monkeypatch):
    # #33: the IK screen's hand probe depends on the world only: built with the world's other caches (set-up,
    # report.setup_s), once; a probe that takes 5 s of the fake clock to build is not the search's time
    from lazyground.drake.ik import hand_probe

    clock = stop.FakeClock(tick=1e-6)
    monkeypatch.setattr(stop, "CLOCK", clock)
    build, builds = hand_probe._build, []

    def slow_build(*args, **kwargs):
        builds.append(args[1])
        clock.advance(5.0)
        return build(*args, **kwargs)

    monkeypatch.setattr(hand_probe, "_build", slow_build)
    report = api.plan("panda_tabletop", "pick up a cup", seed=0, max_iterations=3000)
    assert report.result.solved and builds == ["panda_hand_tcp"]
    assert report.setup_s >= 5.0 and report.result.time_s < 5.0, (report.setup_s, report.result.time_s)
