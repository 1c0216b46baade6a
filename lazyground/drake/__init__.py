"""The Drake side: scene → diagram, coordinates, collision checking, kinematics, IK goal sampling.

Importing this package registers the IK goal source for pose regions
(workspace, placement) with :func:`lazyground.goals.register_goal_source`.
"""

import logging

from lazyground.drake import ik  # noqa: F401  (registers IKGoalSource by region kind; imports pydrake)

# after pydrake's import, which sets it to INFO: every module of this package (check-robot's too) runs this first;
# silences "Allocating contexts to support implicit context parallelism" on every collision checker
logging.getLogger("drake").setLevel(logging.WARNING)
