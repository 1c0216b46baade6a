"""How closely a goal configuration meets its goal region: the IK tolerance, stated once (#20).

A workspace (or placement) goal is met by IK within a tolerance, never exactly:
regions fix some axes (equal bounds), which no numerical solve hits to 1e-6.
Measured on fetch_cans_1 and fetch_boxes_3 (docs/fetch.md): at every tolerance
tried (2 mm / 0.01 rad down to 0.2 mm / 0.001 rad) no goal configuration lay
inside its region to 1e-6, while the cost per solve doubled on cans_1; so the
tolerance is reported (``goal_tolerance`` in the JSON), not tightened.
"""

from __future__ import annotations

import math

POSITION_TOLERANCE = 0.002  # m, half-width of the IK position box around the drawn point
ORIENTATION_TOLERANCE = 0.01  # rad, IK orientation cone around the drawn orientation
SOLVER_SLACK = 1.1  # the solver meets constraints to its feasibility tolerance


def accepted_error(position_tolerance: float = POSITION_TOLERANCE,
                   orientation_tolerance: float = ORIENTATION_TOLERANCE) -> tuple[float, float]:
    """The largest (position m, rotation rad) error of an accepted IK answer from the drawn pose.

    The position box's corner is sqrt(3) half-widths away; both bounds get the solver's slack.
    """
    return SOLVER_SLACK * math.sqrt(3) * position_tolerance, SOLVER_SLACK * orientation_tolerance


def goal_tolerance_json(regions, position_tolerance: float = POSITION_TOLERANCE,
                        orientation_tolerance: float = ORIENTATION_TOLERANCE) -> dict | None:
    """``{"position_m", "orientation_rad"}`` for IK-sampled goals; None when every region is a C-space box (met exactly).

    Args:
        regions: the goal regions the planner was given.
    """
    if all(r.kind == "config" for r in regions):
        return None
    dp, angle = accepted_error(position_tolerance, orientation_tolerance)
    return {"position_m": round(dp, 6), "orientation_rad": round(angle, 6)}
