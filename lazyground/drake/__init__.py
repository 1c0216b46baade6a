"""The Drake side: scene → diagram, coordinates, collision checking, kinematics, IK goal sampling.

Importing this package registers the IK goal source for pose regions
(workspace, placement) with :func:`lazyground.goals.register_goal_source`.
"""

from lazyground.drake import ik  # noqa: F401  (registers IKGoalSource by region kind)
