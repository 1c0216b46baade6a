"""IK goal sampling for pose regions (workspace, placement).

- :mod:`~lazyground.drake.ik.settings`: how hard it tries (:class:`IKSettings`) and its counters.
- :mod:`~lazyground.drake.ik.solvers`: the solver protocol, the batch least-squares solver and the Drake program.
- :mod:`~lazyground.drake.ik.batch`: the damped-least-squares solve on the chain (compiled: :mod:`~lazyground.drake.ik.kernels`).
- :mod:`~lazyground.drake.ik.screen`: the target screen (:mod:`~lazyground.drake.ik.reach`, :mod:`~lazyground.drake.ik.hand_probe`).
- :mod:`~lazyground.drake.ik.attempts`: attempts prepared many at a time for the batch solver.
- :mod:`~lazyground.drake.ik.source`: :class:`IKGoalSource`, round robin over the regions and the approach.

Importing this package registers :class:`IKGoalSource` for workspace and placement regions, without the regions
the world's reach prior proves unreachable (:mod:`lazyground.drake.arm_reach`)
(:func:`lazyground.goals.register_goal_source`).
"""

from lazyground.drake.approach import blocked_approaches
from lazyground.drake.ik.reach import reach_map
from lazyground.drake.ik.settings import DEFAULT_IK_SETTINGS, IKCounters, IKSettings
from lazyground.drake.ik.source import IKGoalSource, region_coordinates
from lazyground.goals import reach_prior_drops, register_goal_source
from lazyground.regions import PlacementRegion, WorkspaceRegion

__all__ = ["DEFAULT_IK_SETTINGS", "IKCounters", "IKGoalSource", "IKSettings", "reach_map", "region_coordinates"]



def _ik_source(regions, world, sampling=None) -> IKGoalSource:
    """The IK source over ``world``, without the regions its reach prior proves unreachable (``reach_prior``); its
    ``blocked_approaches()`` lists the regions whose hand cannot back out (computed when a strategy asks:
    :mod:`lazyground.drake.approach`)."""
    drops = reach_prior_drops(regions, world, sampling)
    source = IKGoalSource(regions, world, sampling=sampling, unreachable=drops)
    source.blocked_approaches = lambda: blocked_approaches(world, tuple(regions), drops)
    return source


register_goal_source((WorkspaceRegion.kind, PlacementRegion.kind), _ik_source)
