"""#20: the HTML replay explains itself: title, request, interpretations (chosen marked), status,
time split, legend, a tree toggle, and labelled pick-and-place steps."""

from __future__ import annotations

import html as html_lib
import re
from dataclasses import replace

from lazyground.viz import meshcat_view
from lazyground.viz.replay_page import PANEL_ID, TOGGLE_ID

from tests.viz.test_meshcat import _step, fetch_can_set_up


def _panel(page: str) -> str:
    start = page.index(f'<div id="{PANEL_ID}">')
    return html_lib.unescape(re.sub(r"<[^>]+>", " ", page[start:page.index("<style>", start)]))


def test_parking_page_has_title_request_interpretations_status_times_and_legend(parking, tmp_path):
    scene, report = parking
    out = tmp_path / "p.html"
    meshcat_view.write_html(report, scene, out)
    page = out.read_text()
    assert "<title>lazyground: &#x27;park&#x27; on parking_1 - solved</title>" in page
    text = " ".join(_panel(page).split())
    assert "“park” on parking_1" in text
    chosen = report.chosen.id
    assert f"solved: reached {chosen} via {report.result.goal_region.id}" in text
    for i in report.grounding.interpretations:  # every interpretation, the chosen one marked
        assert (f"✔ {i.id} (chosen)" if i.id == chosen else i.id) in text
    assert text.count("(chosen)") == 1
    for word in ("grounding", "goal sampling", "collision checking", "other", "iterations", f"seed {report.seed}"):
        assert word in text
    for word in ("goal regions", "goal samples at the car", "the path of the car", "search tree",
                 "goal-biased nodes", "failed goal-biased extensions"):
        assert word in text
    nodes = len(report.result.tree[0])
    # issue 34: the tree started shown and covered the lot; it starts hidden, the button shows it
    assert f'id="{TOGGLE_ID}"' in page and f"Show search tree ({nodes} nodes)" in text
    assert '"/lazyground/step0/tree"' in page  # the button's target
    assert not meshcat_view.EXTERNAL_SCRIPT.search(page)


def test_the_tree_starts_hidden_and_the_button_says_show(parking, tmp_path):
    from pydrake.geometry import Meshcat

    scene, report = parking
    meshcat = Meshcat()
    layout = meshcat_view.draw_layout(report, scene, meshcat)
    assert layout.tree_hidden and layout.tree_paths == ("/lazyground/step0/tree",)
    assert "Show search tree" in meshcat_view.decorate(meshcat.StaticHtml(), report, layout)
    assert meshcat.HasPath("/lazyground/step0/path_tube/0")  # the path drawn as a tube


def test_pick_and_place_steps_are_labelled(tmp_path):
    from lazyground.geometry import Pose
    from lazyground.tasks import Grasp, Outcome, Placement, Step

    scene, world, g, (q0, q1, q2) = fetch_can_set_up(tmp_path)
    pick, place = _step(world, g, q0, q1, g.goal_regions), _step(world, g, q1, q2, g.goal_regions)
    r0 = g.goal_regions[0]
    grasp = Grasp("can1", r0.id, r0.label, "gripper_link", Pose(), Pose())
    placement = Placement("table/top", "table", Pose())  # each place step names its surface (place.run sets it)
    steps = (Step("pick can1", pick.result), Step("place can1", place.result, grasp=grasp, placement=placement))
    outcome = Outcome(pick.result, steps, world.space.names, placement=placement)
    report = replace(pick, outcome=outcome)
    out = tmp_path / "pp.html"
    meshcat_view.write_html(report, scene, out)
    text = " ".join(_panel(out.read_text()).split())
    assert re.search(r"Steps 1\. pick can1 \(0\.0-4\.0 s\) 2\. place can1 on table \(4\.5-8\.5 s\)", text), text


def test_a_one_node_tree_is_one_node(parking):
    # issue 34: the button said "(1 nodes)"
    from pydrake.geometry import Meshcat

    from lazyground.viz.replay_page import panel_html

    scene, report = parking
    layout = meshcat_view.draw_layout(report, scene, Meshcat())
    text = " ".join(_panel(f'{panel_html(report, replace(layout, tree_nodes=1))}<style>').split())
    assert "search tree (1 node)" in text


def test_object_items_say_where_each_object_went_and_in_which_step():
    from lazyground.geometry import Pose
    from lazyground.tasks import ObjectStep, Placement
    from lazyground.viz.replay_page import _object_item

    stowed = ObjectStep("can_r1", "stowed", "side_counter", "chosen among can_r1, can_r2",
                        Placement("side_counter/surface", "side_counter", Pose((0.3, 0.55, 0.23))), 0)
    item = html_lib.unescape(re.sub(r"<[^>]+>", " ", _object_item(stowed)))
    assert "can_r1: stowed -> side_counter at (0.30, 0.55, 0.23), step 1" in item and "chosen among" in item
    assert "can_r2: held, step 3" in _object_item(ObjectStep("can_r2", "held", None, "", None, 2))
