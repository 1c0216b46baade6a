"""How hard IK goal sampling tries (:class:`IKSettings`) and what it has spent (:class:`IKCounters`)."""

from __future__ import annotations

from dataclasses import dataclass

from lazyground.drake.ik.batch import ITERATIONS as BATCH_ITERATIONS
from lazyground.tolerance import ORIENTATION_TOLERANCE, POSITION_TOLERANCE


@dataclass(frozen=True)
class IKSettings:
    """How hard one goal-sampling attempt tries.

    ``restarts`` solves per attempt share the drawn target pose, each from a
    uniform random configuration drawn from the rng, as MoveIt's IK constraint
    sampler seeds them; the batch solver draws them, with ``reach_starts``, among
    the reach map's random arms whose wrist points lie nearest the target's (on
    fetch_boxes_3: 96 % of solves converged within 10 iterations against 85 %,
    valid samples per attempt 0.084 against 0.070 over 20 seeds; samples spread
    a little less: median distance to the region's nearest other sample 1.6 rad
    against 2.3, seeds 0-9, 40 samples). With ``warm_start`` the first starts from the region's
    last valid solution instead: ~1.5x cheaper per sample, but every sample of
    a region then lands on one IK branch (near-copies: median distance to the
    nearest other sample 0.02 rad on fetch_boxes_3 against 1.26 rad), so
    resampling adds no new way in and the one-tree planner stalls (boxes_3,
    reward-penalty at bias 0.5: 1 of 6 seeds within 30 s warm, 4 of 6 random).
    """

    position_tolerance: float = POSITION_TOLERANCE  # m, half-width of the box around the target point
    orientation_tolerance: float = ORIENTATION_TOLERANCE  # rad, angle between target and solved orientation
    restarts: int = 3
    attempt_budget: float | None = 0.25  # s per attempt (also bounded by the planner's deadline); None: no
    # clock, an attempt is bounded by restarts x iterations only (tests: outcomes independent of load)
    major_iterations: int = 60  # SNOPT major iterations; IPOPT max_iter is 3x this
    solver: str = "batch"  # "batch" (numpy damped least squares, many attempts at once), "snopt" or "ipopt"
    batch_attempts: int = 128  # most attempts solved together by "batch" (a look-ahead later draws take from)
    batch_iterations: int = BATCH_ITERATIONS  # damped least-squares iterations per solve
    reach_check: bool = True  # reject targets whose wrist point is far outside the sampled reach
    reach_margin: float = 0.08  # m, distance to the nearest sampled wrist point that still counts
    hand_check: bool = True  # reject targets where the hand alone collides, whatever the arm (drake/ik/hand_probe.py)
    warm_start: bool = False  # first restart from the region's last valid solution (one IK branch)
    seed_near: bool = False  # first restart from the source's ``near`` configuration (the step's start): the IK
    # branch nearest it wins when it is free, other restarts as before (#30). Off by default: on, first's median path
    # fell 10.31 -> 5.04 rad on fetch_boxes_3 and 2.92 -> 1.62 on panda_tabletop (bench, 10 seeds), but a region's
    # samples then sit on one branch (fetch_boxes_3: median distance to the nearest other sample 0.04 rad, as
    # warm_start's 0.02), the spread the one-tree planner's resampling needs (test_ik); IKGoalSource.seed_near
    # turns it on for shortest / fastest's draws after the first solution
    near_first: bool = True  # while a region has no valid sample, its first restart starts from ``near`` (the step's
    # start): the first goal of each region sits on the IK branch nearest the start (no full-turn sweep to reach a
    # nearby object, #30 Deliver 4); later samples spread over branches as before
    near_targets: bool = False  # targets drawn asking the least joint motion from ``near`` (IKGoalSource.seed_near:
    # what shortest / fastest draw after the first solution)
    reach_starts: int = 256  # batch solver: starts drawn among about this many reach-map arms nearest the target (0: uniform)


DEFAULT_IK_SETTINGS = IKSettings()
"""What an IKGoalSource built without settings uses; the test suite swaps in
``IKSettings(attempt_budget=None)`` (tests/conftest.py) so outcomes depend on seeds, not load."""


@dataclass
class IKCounters:
    """Every IK solve made by a source: for success rates and time per solve."""

    solves: int = 0
    successes: int = 0  # solves whose answer met the pose within tolerance
    time: float = 0.0
    success_time: float = 0.0

    def add(self, solves: int, successes: int, seconds: float) -> None:
        """Count ``solves`` solves taking ``seconds`` together, ``successes`` of them successful (time split evenly)."""
        self.solves += solves
        self.successes += successes
        self.time += seconds
        self.success_time += seconds * successes / solves if solves else 0.0

    def to_json(self) -> dict:
        return {
            "solves": self.solves,
            "successes": self.successes,
            "success_rate": round(self.successes / self.solves, 4) if self.solves else None,
            "mean_solve_ms": round(1e3 * self.time / self.solves, 3) if self.solves else None,
            "mean_success_ms": round(1e3 * self.success_time / self.successes, 3) if self.successes else None,
            "mean_failure_ms": round(1e3 * (self.time - self.success_time) / (self.solves - self.successes), 3)
            if self.solves > self.successes else None,
        }
