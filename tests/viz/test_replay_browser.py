"""#20 in a real browser: the page title, the side panel's text and the tree button that works.

Skips where Debian's chromium is not installed (.ci/run installs it).
"""

from __future__ import annotations

import json

import pytest

from lazyground.viz import meshcat_view
from lazyground.viz.replay_page import PANEL_ID, TOGGLE_ID

from .test_browser import CHROMIUM, _browser_check

pytestmark = pytest.mark.skipif(not CHROMIUM.exists(), reason="headless browser test: /usr/bin/chromium not installed")


def test_tree_button_shows_and_hides_the_tree(parking, tmp_path):
    scene, report = parking  # the tree starts hidden
    html = tmp_path / "p.html"
    meshcat_view.write_html(report, scene, html)
    bc = _browser_check()
    with bc.Chromium(timeout=45) as chrome:
        bc.load_replay(chrome, html, timeout=45)
        assert chrome.evaluate("document.title") == f"lazyground: 'park' on parking_1 - {report.result.status.value}"
        panel = chrome.evaluate(f"document.getElementById({json.dumps(PANEL_ID)}).innerText")
        assert "park" in panel and f"{report.chosen.id} (chosen)" in panel and "Legend" in panel
        hidden = bc.shot(chrome)
        click = f"document.getElementById({json.dumps(TOGGLE_ID)}).click(); document.getElementById({json.dumps(TOGGLE_ID)}).textContent"
        assert chrome.evaluate(click).startswith("Hide search tree")
        shown = bc.shot(chrome)
        assert bc.changed_pixels(hidden, shown) > 500  # the tree's edges appeared
        assert chrome.evaluate(click).startswith("Show search tree")
        assert bc.changed_pixels(hidden, bc.shot(chrome)) < 50  # ... and went again
