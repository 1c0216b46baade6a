"""sscbirrt's CBiRRT as a peer, on our collision checker and our goal samples.

As for the OMPL peers (:mod:`lazyground.bench.ompl_peer`), everything but the
search is shared (:mod:`lazyground.bench.peer_setup`):

* the **validity checker** is ``DrakeWorld.config_free`` (the same Drake checker,
  the same padding), behind sscbirrt's ``CollisionChecker`` protocol (``is_valid``);
* **edges** are checked by sscbirrt's default motion validator every
  ``settings.resolution`` (our edge resolution), its step is our step size;
* the **goal** is a ``FiniteSet`` of the goal samples our goal source drew with
  the run's seed (every one a goal-tree root, as in our two-tree planner); the
  start is a one-member ``FiniteSet``;
* the scene's settings for our two-tree planner (its counterpart); path
  smoothing is off, as ours has none;
* **time** starts before grounding and includes goal sampling;
* the returned path is **re-checked** at ``resolution / validation_factor``, as
  ours is before it is returned (inside the timed run); a path that fails is
  counted unsolved (status ``invalid_path``): sscbirrt checks edges at its
  own resolution only, and thin obstacles (shelf boards) slip between.

Because the checker is a Python object, sscbirrt runs its Python reference
backend (its C++ core needs a checker with a native form, e.g. its MuJoCo one):
this compares the search over one checker, not sscbirrt's native speed.
sscbirrt's joint-space metric is unweighted Euclidean with wrapping on
continuous joints; ours weighs coordinates (1 on every Fetch arm joint).
"""

from __future__ import annotations

import numpy as np

PLANNER = "sscbirrt-CBiRRT"  # the planner column of the bench CSV
INVALID_PATH = "invalid_path"  # a run whose returned path collides between its edge checks (counted unsolved)
MISSING = "sscbirrt peer skipped: the 'sscbirrt' package is not installed (pip install .[bench])"



def sscbirrt_available() -> bool:
    try:
        import sscbirrt  # noqa: F401
    except ImportError:
        return False
    return True


class _Robot:
    """Our ConfigSpace as sscbirrt's RobotModel (joint limits and DOF; CBiRRT needs no FK for finite sets)."""

    def __init__(self, space):
        self.dof = space.dim
        self.joint_limits = (np.asarray(space.lower, float), np.asarray(space.upper, float))

    def forward_kinematics(self, q):  # only TSR goals need it
        raise NotImplementedError("the sscbirrt peer plans between finite sets of configurations")


class _Checker:
    """Our Drake checker as sscbirrt's CollisionChecker."""

    def __init__(self, world):
        self.world = world

    def is_valid(self, q: np.ndarray) -> bool:
        return self.world.config_free(np.asarray(q, float))


def run_peer(problem, spec) -> dict:
    """One sscbirrt CBiRRT run as CSV fields (see :func:`plan`)."""
    return plan(problem, spec)[0]


def plan(problem, spec) -> tuple[dict, np.ndarray | None]:
    """One sscbirrt CBiRRT run: (CSV fields, the path with the goal sample's approach segment, or None).

    Raises:
        ImportError: with :data:`MISSING` when sscbirrt is not installed.
    """
    if not sscbirrt_available():
        raise ImportError(MISSING)
    import sscbirrt

    from lazyground.bench.peer_setup import peer_setup
    from lazyground.settings import Algorithm

    setup = peer_setup(problem, spec, Algorithm.BIDIRECTIONAL)
    if not setup.samples:
        return setup.no_goal(), None
    world, settings = setup.world, setup.settings
    config = sscbirrt.CBiRRTConfig(
        timeout=setup.time_left(),
        max_iterations=int(settings.max_iterations),
        step_size=float(settings.step_size),
        edge_resolution=float(settings.resolution),
        smooth_path=False,
        continuous_joints=tuple(bool(w) for w in world.space.wrap),
    )
    checker = _Checker(world)
    planner = sscbirrt.CBiRRT(_Robot(world.space), collision_checker=checker, config=config, backend="python")
    problem_ = sscbirrt.PlanningProblem(
        space=planner.space,
        start=sscbirrt.FiniteSet([world.start]),
        goal=sscbirrt.FiniteSet([s.q for s in setup.samples]),
        validator=checker,
    )
    try:
        result = planner.solve(problem_, seed=spec.seed)
    except sscbirrt.AllStartConfigurationsInCollision as exc:
        return dict(setup.finish(None, str(exc)), status="invalid_start"), None
    path = np.array(result.path, float) if result.success else None
    bad = -1 if path is None else setup.fine_recheck(path)  # inside the peer's time, as ours re-checks inside its own
    out = setup.finish(path if bad < 0 else None, result.failure_reason or "", iterations=result.iterations,
                       tree_size=int(sum(result.tree_sizes)))
    if bad >= 0:
        out.update(status=INVALID_PATH, message=f"the returned path fails the fine re-check at segment {bad}")
        return out, None
    if path is None:
        out["status"] = "timeout"
        return out, None
    return out, setup.full_path(path)
