"""Plan settings under which a test's outcome is a function of its seed: iteration caps decide, the clock never does.

The time limits are out of reach (a guard against a hung run, not a judge); 20,000 iterations is above what any
scene these tests plan reached within its old 10-30 s wall-clock limits (about 500 iterations/s on parking_1).
"""

BY_COUNTS = {"time_limit": 1e6, "max_iterations": 20_000, "shortcut_time": 1e9}
PLANNER_BY_COUNTS = {"time_limit": 1e6, "max_iterations": 20_000}  # PlannerSettings fields only
