"""Executable motion from a planned path (issue #16): shortcutting, a smooth timed trajectory, export.

- :mod:`~lazyground.motion.shortcut`: shorten a path over the planner's protocols (no Drake).
- :mod:`~lazyground.motion.curve`: a smooth curve through a path, checked densely (no Drake).
- :mod:`~lazyground.motion.trajectory`: time parameterisation with Drake's TOPP-RA.
- :mod:`~lazyground.motion.limits`: velocity / acceleration limits from the model and ``robot.yaml``.
- :mod:`~lazyground.motion.pipeline`: shortcut + timing after a solve (what ``api.plan`` runs).
- :mod:`~lazyground.motion.steps`: pick and place: one trajectory per step, gripper events between.
- :mod:`~lazyground.motion.export`: CSV / JSON / ROS ``trajectory_msgs/JointTrajectory`` YAML.
- :mod:`~lazyground.motion.validate`: re-checking a trajectory (tests, ``tools/stress.py``).
"""

TRAJECTORY_FORMATS = (".csv", ".json")  # trajectory file suffixes (export writes them; the CLI checks --trajectory)
