"""Goal regions: what a grounding hands to the goal sampler, one class per kind.

* :class:`ConfigRegion` (``config``) — a box in the planned coordinates;
* :class:`WorkspaceRegion` (``workspace``) — a Berenson-style pose region of an end-effector frame;
* :class:`PlacementRegion` (``placement``) — the same for the carried object's pose.

Adding a kind: write a subclass of :class:`GoalRegion` (or :class:`PoseRegion`)
in its own module here, with ``kind``, :meth:`~GoalRegion.drawing` and, if it has
fields of its own, ``_json_fields``; decorate it with :func:`register_region`
and import it below; then register the goal source that samples it with
:func:`lazyground.goals.register_goal_source` (config regions:
``ConfigGoalSource``; pose regions: ``IKGoalSource``, registered in
:mod:`lazyground.drake.ik`). Nothing else switches on the kind.
"""

from lazyground.regions.base import REGION_KINDS, GoalRegion, RegionDrawing, register_region
from lazyground.regions.config import ConfigRegion
from lazyground.regions.pose import PlacementRegion, PoseRegion, WorkspaceRegion

KINDS = tuple(REGION_KINDS)

__all__ = ["KINDS", "REGION_KINDS", "ConfigRegion", "GoalRegion", "PlacementRegion", "PoseRegion", "RegionDrawing", "WorkspaceRegion", "register_region"]
