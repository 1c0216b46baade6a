"""What every peer planner shares with ours: grounding, settings and the goal samples.

A peer (OMPL, sscbirrt) gets the goal samples our own goal source draws (C-space
boxes or Drake IK) from the same grounding, with the run's seed, and the scene's
settings for its counterpart algorithm; its clock starts before grounding, as ours.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from lazyground.planning.stop import StopCondition
from lazyground.settings import Algorithm


@dataclass(frozen=True)
class PeerSetup:
    """One peer run's shared inputs.

    ``fields`` are the CSV fields known before the search (grounding and goal
    sampling); ``checks0``/``check_time0`` are the checker's counters after goal
    sampling, so that the sampler's own checks count as goal sampling, as in ours.
    """

    world: object
    regions: tuple
    settings: object
    samples: list
    fields: dict
    t0: float
    deadline: float
    check_time0: float
    checks0: int

    def time_left(self) -> float:
        return max(1e-3, self.deadline - time.perf_counter())

    def no_goal(self) -> dict:
        """The CSV fields of a run that found no valid goal sample."""
        return dict(self.fields, status="no_valid_goal", time_s=time.perf_counter() - self.t0, collision_s=0.0,
                    other_s=0.0, message="no valid goal sample")

    def reached(self, path: np.ndarray):
        """The goal sample a peer's path ends at (the nearest to its last configuration)."""
        return min(self.samples, key=lambda s: self.world.space.distance(s.q, path[-1]))

    def full_path(self, path: np.ndarray) -> np.ndarray:
        """The peer's path with the reached sample's checked approach segment appended, as our planner does."""
        final = self.reached(path).final
        return path if final is None else np.vstack([path, final])

    def fine_recheck(self, path: np.ndarray) -> int:
        """The first segment of the full path failing the re-check our planner applies to its own paths (-1: none)."""
        from lazyground.planning import path_is_valid

        fine = self.settings.resolution / self.settings.validation_factor
        return path_is_valid(self.world.space, self.world, self.full_path(path), fine)

    def finish(self, path: np.ndarray | None, message: str, **extra) -> dict:
        """The CSV fields once the search ended: ``path`` (None: unsolved) gets the reached sample's approach."""
        time_s = time.perf_counter() - self.t0
        out = dict(self.fields, time_s=time_s, collision_s=self.world.check_time - self.check_time0,
                   collision_checks=self.world.checks - self.checks0, message=message, **extra)
        if path is not None:
            reached = self.reached(path)
            path = self.full_path(path)
            region = self.regions[reached.region]
            out.update(status="solved", interpretation=region.interpretation, region=region.id,
                       path_length=self.world.space.path_length(path), message="")
        out["other_s"] = max(0.0, time_s - out["goal_sampling_s"] - out["collision_s"] - out["grounding_s"])
        return out


def peer_setup(problem, spec, counterpart: Algorithm) -> PeerSetup:
    """Ground the request and draw the first batch of goal samples for a peer run.

    Args:
        problem: the loaded benchmark problem (runner.Problem).
        spec: the run (runner.RunSpec): seed and time limit.
        counterpart: our algorithm whose scene settings (step size, resolution) the peer runs with.
    """
    from lazyground.api import make_goal_source, planner_settings
    from lazyground.bench import arms
    from lazyground.goals import ConfigGoalSource

    stop = StopCondition.after(spec.time_limit, clock=time.perf_counter)  # the peers read perf_counter too
    t0, deadline = stop.start, stop.deadline
    world = problem.world
    regions, grounding_s = problem.ground()
    if problem.regions:
        settings = planner_settings(problem.scene, edge_resolution=arms.EDGE_RESOLUTION, algorithm=counterpart)
        source = ConfigGoalSource(regions, world.space, world)
    else:
        settings = planner_settings(problem.scene, algorithm=counterpart)
        source = make_goal_source(world, regions)
    rng = np.random.default_rng(spec.seed)
    samples = []
    while not samples and not source.exhausted() and not stop.should_stop():
        samples = source.draw(settings.initial_goal_samples, rng, stop)
    fields = dict(grounding_s=grounding_s, goal_sampling_s=source.sample_time, goal_samples=len(samples), resamplings=0,
                  goal_attempts=sum(st.attempts for st in source.stats))
    return PeerSetup(world, tuple(regions), settings, samples, fields, t0, deadline, world.check_time, world.checks)
