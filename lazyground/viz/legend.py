"""The parking figure's legend: one entry for every kind of mark the figure draws (#20)."""

from __future__ import annotations

from matplotlib.lines import Line2D
from matplotlib.patches import FancyArrow, Patch

from lazyground.viz.style import (CAR_RGBA, FAILED_RGBA, GOAL_BIASED_RGBA, LIMITS_RGBA, OBSTACLE_RGBA, PATH_RGBA, REGION_RGBA,
                                  TREE_RGBA, weight_rgba)

LABEL_STYLE = dict(fontsize=6, color=(0, 0.35, 0.1), ha="center", va="center", zorder=11,
                   bbox=dict(boxstyle="round,pad=0.15", fc=(1, 1, 1, 0.75), ec="none"))  # above the car (zorder 8)
OCCUPIED_LABEL_STYLE = LABEL_STYLE | dict(color=(0.3, 0.3, 0.3))
LIMITS_STYLE = dict(fill=False, ec=LIMITS_RGBA, ls=(0, (6, 2, 1, 2)), lw=1.2)


class _ArrowHandler:
    """Draws a legend entry as a small arrow in the handle's colour (the goal samples are arrows)."""

    def legend_artist(self, legend, orig_handle, fontsize, handlebox):
        w, h = handlebox.width, handlebox.height
        arrow = FancyArrow(0, h / 2, w, 0, width=0.25 * h, head_width=0.8 * h, head_length=0.35 * w,
                           length_includes_head=True, color=orig_handle.get_color(), transform=handlebox.get_transform())
        handlebox.add_artist(arrow)
        return arrow


class _ArrowHandle(Line2D):
    """A legend proxy drawn by :class:`_ArrowHandler`."""


def parking_handles(has_tree: bool, has_failed: bool, has_path: bool, has_occupied: bool, outlines: bool = True,
                    has_limits: bool = False) -> list:
    """Legend proxies for what the parking figure shows, in reading order (``outlines``: car outlines along the path;
    ``has_limits``: the lot's limits are drawn)."""
    handles = [Patch(**LIMITS_STYLE, label="lot limits (robot.limits)")] if has_limits else []
    handles += [
        Patch(fc="none", ec="black", ls="--", label="start (car outline)"),
        Patch(fc=OBSTACLE_RGBA, ec="none", label="obstacle"),
        Patch(fc=REGION_RGBA, ec=REGION_RGBA[:3], label="free spot (goal region)"),
    ]
    if has_occupied:
        handles.append(Patch(fc=OBSTACLE_RGBA, ec="black", label="parked car (occupied spot)"))
    handles.append(_ArrowHandle([], [], color=weight_rgba(1.0), label="goal sample: heading, colour = weight"))
    if has_tree:
        handles.append(Line2D([], [], color=TREE_RGBA, lw=1.0, label="search tree"))
        handles.append(Line2D([], [], ls="none", marker="o", ms=3, color=GOAL_BIASED_RGBA, label="goal-biased extension / goal tree"))
    if has_failed:
        handles.append(Line2D([], [], ls="none", marker="x", ms=4, color=FAILED_RGBA, label="failed goal-biased extension from"))
    if has_path:
        handles.append(Line2D([], [], color=PATH_RGBA, lw=2.5, label="path"))
        if outlines:
            handles.append(Patch(fc="none", ec=PATH_RGBA, label="car outline along the path"))
        handles.append(Patch(fc=CAR_RGBA, ec="black", label="car at the goal"))
    return handles


HANDLER_MAP = {_ArrowHandle: _ArrowHandler()}
