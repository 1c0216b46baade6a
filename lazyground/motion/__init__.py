"""Executable motion from a planned path: shortcutting, a smooth timed trajectory, export.

- :mod:`~lazyground.motion.shortcut`: shorten a path over the planner's protocols (no Drake).
- :mod:`~lazyground.motion.curve`: a smooth curve through a path, checked densely (no Drake).
- :mod:`~lazyground.motion.trajectory`: time parameterisation with Drake's TOPP-RA.
- :mod:`~lazyground.motion.export`: CSV / JSON / ROS ``trajectory_msgs/JointTrajectory`` YAML.
- :mod:`~lazyground.motion.pipeline`: shortcut + timing after a solve (what the API runs).
"""
