"""Planning over numpy arrays and small protocols; no Drake here."""

from lazyground.planning.problem import GoalSample, PlannerSettings, PlanResult, PlanStatus, RegionStats
from lazyground.planning.rrt import path_is_valid, solve
from lazyground.planning.space import ConfigSpace
from lazyground.planning.strategies import STRATEGIES, make_strategy

__all__ = [
    "STRATEGIES", "ConfigSpace", "GoalSample", "PlanResult", "PlanStatus", "PlannerSettings", "RegionStats",
    "make_strategy", "path_is_valid", "solve",
]
