"""The text around an HTML replay (#20): page title and a side panel that explains the plan.

Meshcat's static page has no words of its own. :func:`decorate` gives it a title
and a panel, inside the same self-contained file (no request leaves it): the
request, every interpretation with the chosen one marked, the status, the time
split, the replay's steps (pick, then place) with the current one highlighted
while the animation plays, a colour legend, and a button that shows or hides
the search tree (large trees start hidden: they cover the objects).
"""

from __future__ import annotations

import html
import json
from dataclasses import dataclass

from lazyground.viz.style import FAILED_RGBA, GOAL_BIASED_RGBA, PATH_RGBA, REGION_RGBA, TREE_RGBA, weight_rgba

PANEL_ID = "lazyground-panel"
TOGGLE_ID = "lazyground-tree-toggle"
PANEL_WIDTH = 300  # px


@dataclass(frozen=True)
class Layout:
    """What :func:`lazyground.viz.meshcat_view.draw_layout` drew: replay length, step windows, tree paths."""

    seconds: float
    windows: tuple[tuple[str, float, float], ...]  # (step label, start s, end s) in the recording
    tree_paths: tuple[str, ...]  # Meshcat paths of the search trees (one per step)
    tree_nodes: int
    tree_hidden: bool  # whether the trees start hidden
    arm: bool  # an arm (tracer = end effector) or a mobile base


def _css(rgba) -> str:
    r, g, b, a = rgba
    return f"rgba({round(255 * r)}, {round(255 * g)}, {round(255 * b)}, {max(a, 0.45):.2f})"


def title(report) -> str:
    """The page title: request, scene, status."""
    return f"lazyground: '{report.request}' on {report.scene} - {report.result.status.value}"


def _status(report) -> str:
    res = report.result
    if res.solved and report.chosen is not None:
        return f"solved: reached <b>{html.escape(report.chosen.id)}</b> via {html.escape(res.goal_region.id)}"
    return f"{html.escape(res.status.value)}: {html.escape(res.message or '')}"


def _interpretations(report) -> str:
    chosen = report.chosen.id if report.chosen is not None else None
    rows = []
    for i in report.grounding.interpretations:
        mark, cls = ("&#10004; ", "chosen") if i.id == chosen else ("", "")
        rows.append(f'<li class="{cls}">{mark}{html.escape(i.id)}{" (chosen)" if cls else ""}</li>')
    return "".join(rows)


def _times(report) -> str:
    res = report.result
    parts = [("grounding", report.grounding_s), ("goal sampling", res.goal_sampling_s),
             ("collision checking", res.collision_s), ("other", res.other_s)]
    split = ", ".join(f"{name} {t:.3f}" for name, t in parts)
    return (f"time {report.time_s:.3f} s ({split}); {res.iterations} iterations, tree {res.tree_size}, "
            f"{len(res.goal_samples)} goal samples; seed {report.seed}, {html.escape(report.settings.planner.strategy)}, "
            f"{html.escape(report.settings.planner.algorithm)}")


def _legend(layout: Layout) -> str:
    tracer = "gripper" if layout.arm else "car"
    items = [
        (_css(REGION_RGBA), "goal regions (translucent green)"),
        (f"linear-gradient(90deg, {_css(weight_rgba(0))}, {_css(weight_rgba(0.5))}, {_css(weight_rgba(1))})",
         f"goal samples at the {tracer}, by reward-penalty weight (red 0 to green 1)"),
        (_css(PATH_RGBA), f"the path of the {tracer}"),
        (_css(TREE_RGBA), "search tree"),
        (_css(GOAL_BIASED_RGBA), "goal-biased nodes / goal trees"),
        (_css(FAILED_RGBA), "failed goal-biased extensions start here"),
    ]
    return "".join(f'<li><span class="sw" style="background:{c}"></span>{html.escape(t)}</li>' for c, t in items)


def _object_item(o) -> str:
    """One object of a several-object request (#30): done / stowed / held / already there / not done, where
    (the surface, the position it was put down at, the step), why."""
    where = f" -> {o.target}" if o.target else ""
    if getattr(o, "placement", None) is not None:
        x, y, z = o.placement.X_WO.xyz
        where += f" at ({x:.2f}, {y:.2f}, {z:.2f})"
    if getattr(o, "step", None) is not None:
        where += f", step {o.step + 1}"
    why = f' <span class="dim">({html.escape(o.why)})</span>' if o.why else ""
    return f"<li>{html.escape((o.object or '-') + ': ' + o.status + where)}{why}</li>"


def panel_html(report, layout: Layout) -> str:
    """The side panel (HTML, CSS and a little JavaScript over Meshcat's global ``viewer``)."""
    steps = "".join(f'<li data-t0="{t0:.3f}" data-t1="{t1:.3f}">{html.escape(label)} '
                    f'<span class="dim">({t0:.1f}-{t1:.1f} s)</span></li>' for label, t0, t1 in layout.windows)
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in tuple(report.grounding.notes) + tuple(report.notes))
    objects = "".join(_object_item(o) for o in (report.outcome.objects if report.outcome is not None else ()))
    button = ""
    if layout.tree_paths:
        word = "Show" if layout.tree_hidden else "Hide"
        button = f'<button id="{TOGGLE_ID}" type="button">{word} search tree ({layout.tree_nodes} node{"" if layout.tree_nodes == 1 else "s"})</button>'
    return f"""
<div id="{PANEL_ID}">
  <div class="req">&ldquo;{html.escape(report.request)}&rdquo; <span class="dim">on {html.escape(report.scene)}</span></div>
  <div class="status {'ok' if report.result.solved else 'bad'}">{_status(report)}</div>
  <h4>Interpretations ({len(report.grounding.interpretations)})</h4><ul class="interps">{_interpretations(report)}</ul>
  {f'<h4>Steps</h4><ul class="steps">{steps}</ul>' if len(layout.windows) > 1 else ''}
  {f'<h4>Objects</h4><ul class="objects small">{objects}</ul>' if objects else ''}
  <div class="dim small">{_times(report)}</div>
  {f'<ul class="notes small">{notes}</ul>' if notes else ''}
  {button}
  <h4>Legend</h4><ul class="legend small">{_legend(layout)}</ul>
</div>
<style>
  /* a side panel, not an overlay on the robot: the 3-D view takes the rest of the window */
  #meshcat-pane {{ position: absolute; left: {PANEL_WIDTH}px; top: 0; width: calc(100vw - {PANEL_WIDTH}px) !important; }}
  #{PANEL_ID} {{ position: fixed; top: 0; left: 0; width: {PANEL_WIDTH - 20}px; height: calc(100vh - 16px); overflow: auto;
    background: #fafafa; color: #111; font: 13px/1.35 sans-serif; padding: 8px 10px;
    border-right: 1px solid #bbb; z-index: 10; }}
  #{PANEL_ID} h4 {{ margin: 8px 0 2px; font-size: 12px; }}
  #{PANEL_ID} ul, #{PANEL_ID} ol {{ margin: 0; padding-left: 18px; }}
  #{PANEL_ID} .legend {{ list-style: none; padding-left: 0; }}
  #{PANEL_ID} .req {{ font-weight: bold; font-size: 14px; }}
  #{PANEL_ID} .status.ok {{ color: #06612a; }} #{PANEL_ID} .status.bad {{ color: #a00; }}
  #{PANEL_ID} .chosen {{ font-weight: bold; color: #06612a; }}
  #{PANEL_ID} .steps li.now {{ font-weight: bold; background: #dff3ff; }}
  #{PANEL_ID} .dim {{ color: #555; }} #{PANEL_ID} .small {{ font-size: 11px; }}
  #{PANEL_ID} .sw {{ display: inline-block; width: 22px; height: 10px; margin-right: 6px; border: 1px solid #888; }}
  #{PANEL_ID} button {{ margin-top: 6px; font-size: 12px; }}
</style>
<script>
(function () {{
  var trees = {json.dumps(list(layout.tree_paths))}, shown = {json.dumps(not layout.tree_hidden)};
  var button = document.getElementById("{TOGGLE_ID}");
  function setTrees(visible) {{
    trees.forEach(function (p) {{ viewer.handle_command({{type: "set_property", path: p, property: "visible", value: visible}}); }});
  }}
  if (button) button.addEventListener("click", function () {{
    shown = !shown; setTrees(shown);
    button.textContent = button.textContent.replace(shown ? "Show" : "Hide", shown ? "Hide" : "Show");
  }});
  var steps = document.querySelectorAll("#{PANEL_ID} .steps li");
  if (steps.length) setInterval(function () {{
    var t = (typeof viewer !== "undefined" && viewer.animator) ? viewer.animator.time : -1;
    steps.forEach(function (li) {{ li.classList.toggle("now", t >= +li.dataset.t0 && t <= +li.dataset.t1 + 0.5); }});
  }}, 200);
}})();
</script>
"""


def decorate(page: str, report, layout: Layout) -> str:
    """Meshcat's static page with the title replaced and the panel added before ``</body>``."""
    page = page.replace("<title>Drake MeshCat</title>", f"<title>{html.escape(title(report))}</title>", 1)
    at = page.rfind("</body>")
    return page[:at] + panel_html(report, layout) + page[at:] if at >= 0 else page + panel_html(report, layout)
