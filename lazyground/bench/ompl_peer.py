"""OMPL's RRT and RRTConnect as peers, on our collision checker and our goal samples.

The race is meant to be fair, so everything but the search is shared:

* the **validity checker** is a Python callable over ``DrakeWorld.config_free``
  (the same Drake checker, the same padding);
* **motion validation** is OMPL's discrete validator at the same resolution as
  ours (``setStateValidityCheckingResolution(resolution / maximum extent)``);
* the **goal** is ``ob.GoalStates`` holding goal samples drawn by the very goal
  source our planner uses (C-space boxes or Drake IK) from the same grounding;
  OMPL's RRT visits them round-robin when it takes a goal-biased step;
* the **range** is our step size, RRT's goal bias is the run's bias;
* **time** starts before grounding and includes goal sampling, as for ours.

The state space is a ``CompoundStateSpace``: one ``RealVectorStateSpace`` with
the same bounds over the linear coordinates plus one ``SO2StateSpace`` per
wrapping angle (the car's heading), weighted like our metric. OMPL sums the
subspace distances (L1 over subspaces) where we take a Euclidean norm of the
embedding, so distances differ slightly (e.g. for the car: |dxy| + w|dθ| vs
sqrt(|dxy|² + (2w sin(dθ/2))²)); with no angles both are Euclidean. Per-joint
weights other than 1 on linear coordinates are not reproduced (OMPL's real
vector space has none).

OMPL seeds its random numbers per process (``RNG.setSeed`` works only before
the first sampler exists), so peer runs are not reproducible seed by seed;
the goal samples are (they come from our seeded generator).
"""

from __future__ import annotations

import gc
import time

import numpy as np

MISSING = "OMPL peers skipped: the 'ompl' package is not installed (pip install .[bench])"


def ompl_available() -> bool:
    try:
        import ompl.base  # noqa: F401
    except ImportError:
        return False
    return True


def _quiet() -> None:
    from ompl import util as ou

    ou.noOutputHandler()  # planners would print "Info:" lines into the progress bar


class _Space:
    """Our ConfigSpace as an OMPL compound space, with conversions both ways."""

    def __init__(self, space):
        from ompl import base as ob

        self.lin = np.flatnonzero(~space.wrap)
        self.ang = np.flatnonzero(space.wrap)
        self.dim = space.dim
        self.ompl = ob.CompoundStateSpace()
        if len(self.lin):
            rv = ob.RealVectorStateSpace(len(self.lin))
            bounds = ob.RealVectorBounds(len(self.lin))
            for k, i in enumerate(self.lin):
                bounds.setLow(k, float(space.lower[i]))
                bounds.setHigh(k, float(space.upper[i]))
            rv.setBounds(bounds)
            self.ompl.addSubspace(rv, 1.0)
        for i in self.ang:
            self.ompl.addSubspace(ob.SO2StateSpace(), float(space.weights[i]))
        self._off = 1 if len(self.lin) else 0

    def to_numpy(self, state) -> np.ndarray:
        q = np.empty(self.dim)
        if len(self.lin):
            rv = state[0]
            for k, i in enumerate(self.lin):
                q[i] = rv[k]
        for k, i in enumerate(self.ang):
            q[i] = state[self._off + k].value
        return q

    def to_ompl(self, q: np.ndarray):
        state = self.ompl.allocState()
        if len(self.lin):
            rv = state[0]
            for k, i in enumerate(self.lin):
                rv[k] = float(q[i])
        for k, i in enumerate(self.ang):
            state[self._off + k].value = float(q[i])
        return state


def run_peer(problem, spec) -> dict:
    """One OMPL run (``spec.planner`` is "ompl-RRT" or "ompl-RRTConnect") as CSV fields.

    Raises:
        ImportError: with :data:`MISSING` when ompl is not installed.
    """
    if not ompl_available():
        raise ImportError(MISSING)
    from ompl import base as ob
    from ompl import geometric as og

    from lazyground.api import make_goal_source, planner_settings
    from lazyground.settings import Algorithm
    from lazyground.bench import arms
    from lazyground.goals import ConfigGoalSource

    _quiet()
    t0 = time.perf_counter()
    deadline = t0 + spec.time_limit
    world = problem.world
    regions, grounding_s = problem.ground()
    # each peer runs with the scene's settings for its counterpart: RRT ~ our one tree, RRTConnect ~ two trees
    counterpart = Algorithm.RRT if spec.planner == "ompl-RRT" else Algorithm.BIDIRECTIONAL
    if problem.regions:
        settings = planner_settings(problem.scene, edge_resolution=arms.EDGE_RESOLUTION, algorithm=counterpart)
        source = ConfigGoalSource(regions, world.space, world)
    else:
        settings = planner_settings(problem.scene, algorithm=counterpart)
        source = make_goal_source(world, regions)
    rng = np.random.default_rng(spec.seed)
    samples = []
    while not samples and not source.exhausted() and time.perf_counter() < deadline:
        samples = source.draw(settings.initial_goal_samples, rng, deadline)
    fields = dict(grounding_s=grounding_s, goal_sampling_s=source.sample_time, goal_samples=len(samples), resamplings=0)
    if not samples:
        return dict(fields, status="no_valid_goal", time_s=time.perf_counter() - t0, collision_s=0.0,
                    other_s=0.0, message="no valid goal sample")
    check0 = world.check_time  # the sampler's own checks count as goal sampling, as in our planner

    space = _Space(world.space)
    si = ob.SpaceInformation(space.ompl)
    si.setStateValidityChecker(lambda s: world.config_free(space.to_numpy(s)))
    si.setStateValidityCheckingResolution(settings.resolution / space.ompl.getMaximumExtent())
    si.setup()
    pdef = ob.ProblemDefinition(si)
    pdef.addStartState(space.to_ompl(world.start))
    goal = ob.GoalStates(si)
    for s in samples:
        goal.addState(space.to_ompl(s.q))
    pdef.setGoal(goal)
    planner = og.RRT(si) if spec.planner == "ompl-RRT" else og.RRTConnect(si)
    planner.setRange(settings.step_size)
    if spec.planner == "ompl-RRT":
        planner.setGoalBias(float(spec.bias))
    planner.setProblemDefinition(pdef)
    planner.setup()
    status = planner.solve(max(1e-3, deadline - time.perf_counter()))
    time_s = time.perf_counter() - t0
    solved = pdef.hasExactSolution()
    data = ob.PlannerData(si)
    planner.getPlannerData(data)
    out = dict(fields, time_s=time_s, collision_s=world.check_time - check0, tree_size=data.numVertices(), message=str(status))
    if solved:
        path_ = pdef.getSolutionPath()
        path = np.array([space.to_numpy(path_.getState(i)) for i in range(path_.getStateCount())])
        reached = min(samples, key=lambda s: world.space.distance(s.q, path[-1]))
        if reached.final is not None:  # the sampler's checked approach segment, as our planner appends it
            path = np.vstack([path, reached.final])
        region = regions[reached.region]
        out.update(status="solved", interpretation=region.interpretation, region=region.id,
                   path_length=world.space.path_length(path), message="")
    else:
        out["status"] = "invalid_start" if "Invalid start" in str(status) else "timeout"
    out["other_s"] = max(0.0, time_s - out["goal_sampling_s"] - out["collision_s"] - grounding_s)
    del planner, pdef, goal, si, data  # free OMPL objects now, not at interpreter exit
    gc.collect()
    return out
