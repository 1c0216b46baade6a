"""Goal sampling for workspace goal regions by inverse kinematics.

One attempt on a region: draw a 6-vector v in the region, turn it into a
target pose of the end-effector frame, solve Drake ``InverseKinematics`` for
that pose over the planned coordinates (kinematics only: position box and
orientation cone, joint limits as variable bounds), then confirm the answer
with the collision checker. No minimum-distance constraint: with one, failed
solves cost 0.3-0.8 s each (issue 7); without it a failed solve stops at the
iteration limit after a few milliseconds, and collisions are checked after.
"""

from __future__ import annotations

import time
from collections import OrderedDict
from dataclasses import dataclass

import numpy as np
from pydrake.math import RotationMatrix
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.multibody.tree import RevoluteJoint
from pydrake.solvers import IpoptSolver, SnoptSolver, SolverOptions
from scipy.spatial import cKDTree

from lazyground.drake.chain import chain_to_frame, joints_to_world
from lazyground.geometry import Pose
from lazyground.goals import RoundRobinGoalSource, register_goal_source
from lazyground.planning.problem import GoalSample
from lazyground.regions import PlacementRegion, PoseRegion, WorkspaceRegion
from lazyground.scene.typed_yaml import SceneError
from lazyground.tolerance import ORIENTATION_TOLERANCE, POSITION_TOLERANCE, accepted_error


APPROACH_RESOLUTION = 0.01  # rad (or m): spacing of the collision checks along an approach segment
APPROACH_SCALES = (1.0, 0.5, 0.25)  # fractions of a region's approach distance tried in turn


@dataclass(frozen=True)
class IKSettings:
    """How hard one goal-sampling attempt tries.

    ``restarts`` solves per attempt share the drawn target pose, each from a
    uniform random configuration drawn from the rng, as MoveIt's IK constraint
    sampler seeds them. With ``warm_start`` the first starts from the region's
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
    # clock, an attempt is bounded by restarts x major_iterations only (tests: outcomes independent of load)
    major_iterations: int = 60  # SNOPT major iterations; IPOPT max_iter is 3x this
    solver: str = "snopt"  # "snopt" or "ipopt"
    reach_check: bool = True  # reject targets whose wrist point is far outside the sampled reach
    reach_margin: float = 0.08  # m, distance to the nearest sampled wrist point that still counts
    warm_start: bool = False  # first restart from the region's last valid solution (one IK branch)


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


class IKGoalSource(RoundRobinGoalSource):
    """Valid goal configurations for pose regions (workspace, placement), by IK.

    Args:
        regions: :class:`~lazyground.regions.PoseRegion` goal regions (placement
            regions need a world carrying an attached object).
        world: the :class:`~lazyground.drake.world.DrakeWorld` to solve in.
        settings: IK tolerances and per-attempt limits (default: DEFAULT_IK_SETTINGS).
        **kwargs: :class:`RoundRobinGoalSource` options.

    A sample records ``extra = {"X_WG": Pose, "v": 6-vector, "frame": name}``.
    """

    def __init__(self, regions: tuple[PoseRegion, ...], world, settings: IKSettings | None = None, **kwargs):
        super().__init__(regions, **kwargs)
        settings = DEFAULT_IK_SETTINGS if settings is None else settings
        attached = getattr(world, "attached", None)
        for r in self.regions:
            if not isinstance(r, PoseRegion):
                raise ValueError(f"region {r.id} is a {r.kind} region, not a pose region; use its registered goal source")
            frame = r.robot_target(r.X_WR, attached)[0]  # raises for a placement without a carried object
            if not world.plant.HasFrameNamed(frame):  # a scene/request mismatch, not a bug
                raise SceneError(f"{world.scene.source}: robot: no frame {frame!r} to reach goal region {r.id} with (set robot.end_effector)")
        self.world = world
        self.settings = settings
        self.counters = IKCounters()
        self.region_counters = [IKCounters() for _ in self.regions]
        self._plant = world.plant
        self._kinematics = world.kinematics
        self._planned = np.asarray(world.planned, int)
        self._lower = world.q_full.copy()
        self._upper = world.q_full.copy()
        self._lower[self._planned] = world.space.lower
        self._upper[self._planned] = world.space.upper
        self._last: list[np.ndarray | None] = [None] * len(self.regions)
        if settings.solver == "snopt" and SnoptSolver().available() and SnoptSolver().enabled():
            self._solver = SnoptSolver()
            self._options = SolverOptions()
            self._options.SetOption(SnoptSolver.id(), "Major iterations limit", settings.major_iterations)
        else:
            self._solver = IpoptSolver()
            self._options = SolverOptions()
            self._options.SetOption(IpoptSolver.id(), "max_iter", 3 * settings.major_iterations)
            self._options.SetOption(IpoptSolver.id(), "print_level", 0)

    # --- hooks -------------------------------------------------------------------------------
    def target_pose_for(self, region: PoseRegion, v: np.ndarray, approach: bool = False) -> tuple[str, Pose]:
        """The robot frame to constrain and its target pose X_WT for a draw ``v`` of ``region``.

        The region says which frame (:meth:`PoseRegion.robot_target`): a workspace
        region its end-effector frame, a placement region the body carrying the
        world's attached object. With ``approach``, the pre-pose: the target moved
        by ``region.approach`` in its own axes.
        """
        X_WT = region.pose_in_world(v)
        if approach:
            X_WT = X_WT.compose(Pose(tuple(region.approach)))
        return region.robot_target(X_WT, getattr(self.world, "attached", None))

    def approach_from(self, region: PoseRegion, v: np.ndarray, q_full: np.ndarray, scale: float = 1.0) -> np.ndarray | None:
        """The pre-pose configuration for a goal at ``q_full``, if its straight approach is free.

        The pre-pose is ``scale`` times the region's approach away. It is solved
        from ``q_full`` so it stays on the same IK branch; the joint-space segment
        from it to the goal is collision-checked every APPROACH_RESOLUTION.
        """
        frame, X_pre = self.target_pose_for(region, v, approach=True)
        if scale != 1.0:
            X_goal = self.target_pose_for(region, v)[1].matrix()
            X = X_pre.matrix()
            X[:3, 3] = X_goal[:3, 3] + scale * (X[:3, 3] - X_goal[:3, 3])
            X_pre = Pose.from_matrix(X)
        pre_full = self.solve(frame, X_pre, q_full)
        if pre_full is None:
            return None
        pre, q = pre_full[self._planned], q_full[self._planned]
        if not self.world.space.within_bounds(pre):
            return None
        if not np.all(self.world.configs_free(self.world.space.discretize(pre, q, APPROACH_RESOLUTION))):
            return None
        return pre

    # --- one attempt -------------------------------------------------------------------------
    def attempt(self, j: int, rng: np.random.Generator, deadline: float) -> tuple[GoalSample | None, str]:
        region = self.regions[j]
        v = region.sample(rng)
        frame, X_WT = self.target_pose_for(region, v)
        if self.settings.reach_check and not reach_map(self.world, frame).plausible(X_WT.matrix(), self.settings.reach_margin):
            return None, "out of reach"
        budget = self.settings.attempt_budget
        stop = deadline if budget is None else min(deadline, time.perf_counter() + budget)
        seeds = [self._last[j]] if self._last[j] is not None and self.settings.warm_start else []
        reason = "time"
        for k in range(self.settings.restarts):
            if time.perf_counter() >= stop:
                break
            seed = seeds[k] if k < len(seeds) else self._random_full(rng)
            q_full = self.solve(frame, X_WT, seed, counters=self.region_counters[j])
            if q_full is None:
                reason = "ik failed" if reason != "in collision" else reason
                continue
            q = q_full[self._planned]
            if not self.world.space.within_bounds(q):
                reason = "outside limits"
                continue
            if not self.world.config_free(q):
                reason = "in collision"  # another restart may find a collision-free branch
                continue
            self._last[j] = q_full
            # Aim at a pre-pose when its straight approach is free: the full distance, then
            # shorter ones; under a low shelf board only the goal itself may be left.
            for scale in APPROACH_SCALES if any(region.approach) else ():
                pre = self.approach_from(region, v, q_full, scale)
                if pre is not None:
                    extra = {"X_WG": X_WT, "v": v, "frame": frame, "approach_scale": scale}
                    return GoalSample(q=pre, region=j, final=q, extra=extra), ""
            return GoalSample(q=q, region=j, extra={"X_WG": X_WT, "v": v, "frame": frame}), ""
        return None, reason

    def solve(self, frame: str, X_WT: Pose, seed_full: np.ndarray, counters: IKCounters | None = None) -> np.ndarray | None:
        """Full plant positions putting ``frame`` at ``X_WT`` (within tolerance), or None."""
        s = self.settings
        plant = self._plant
        t0 = time.perf_counter()
        ik = InverseKinematics(plant, with_joint_limits=False)
        q = ik.q()
        prog = ik.get_mutable_prog()
        prog.AddBoundingBoxConstraint(self._lower, self._upper, q)
        G = plant.GetFrameByName(frame)
        X = X_WT.matrix()
        p_WT = X[:3, 3]
        tol = np.full(3, s.position_tolerance)
        ik.AddPositionConstraint(G, np.zeros(3), plant.world_frame(), p_WT - tol, p_WT + tol)
        ik.AddOrientationConstraint(plant.world_frame(), RotationMatrix(X[:3, :3]), G, RotationMatrix(), s.orientation_tolerance)
        result = self._solver.Solve(prog, np.clip(seed_full, self._lower, self._upper), self._options)
        q_sol = np.asarray(result.GetSolution(q), float)
        ok = bool(np.all(np.isfinite(q_sol)))
        if ok:  # judge the answer by forward kinematics, not by the solver's status
            dp, angle = self.pose_error(frame, q_sol, X_WT)
            max_dp, max_angle = accepted_error(s.position_tolerance, s.orientation_tolerance)
            ok = dp <= max_dp and angle <= max_angle
        dt = time.perf_counter() - t0
        for c in (self.counters, counters):
            if c is not None:
                c.solves += 1
                c.time += dt
                if ok:
                    c.successes += 1
                    c.success_time += dt
        return q_sol if ok else None

    # --- kinematics helpers ------------------------------------------------------------------
    def frame_pose(self, frame: str, q_full: np.ndarray) -> np.ndarray:
        """World pose (4x4) of a frame at full plant positions ``q_full``."""
        return self._kinematics.matrix(frame, q_full)

    def pose_error(self, frame: str, q_full: np.ndarray, X_WT: Pose) -> tuple[float, float]:
        """(position error in m, rotation angle in rad) of ``frame`` at ``q_full`` from ``X_WT``."""
        X = self.frame_pose(frame, q_full)
        T = X_WT.matrix()
        R = T[:3, :3].T @ X[:3, :3]
        angle = float(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))
        return float(np.linalg.norm(X[:3, 3] - T[:3, 3])), angle

    def _random_full(self, rng: np.random.Generator) -> np.ndarray:
        q = self.world.q_full.copy()
        q[self._planned] = self.world.space.sample(rng)
        return q

    def ik_report(self) -> dict:
        """IK counters overall and per region (JSON-ready)."""
        return {"all": self.counters.to_json(), **{r.id: c.to_json() for r, c in zip(self.regions, self.region_counters)}}


def region_coordinates(region: PoseRegion, X_WG: np.ndarray) -> np.ndarray:
    """The end-effector pose ``X_WG`` (4x4) as a 6-vector in the region's sampled frame (:meth:`PoseRegion.coordinates_of`)."""
    return region.coordinates_of(X_WG)


register_goal_source((WorkspaceRegion.kind, PlacementRegion.kind), IKGoalSource)


# --- a cheap reachability filter ------------------------------------------------------------
REACH_SAMPLES = 10000
REACH_SEED = 20190520  # the map is a deterministic property of the robot, not of a plan's rng
REACH_CACHE_SIZE = 8  # reach maps kept at once (robots x end-effector frames); ~0.3 MB each
_REACH_MAPS: "OrderedDict[tuple, ReachMap]" = OrderedDict()  # reach_key -> map, least recently used first


@dataclass(frozen=True)
class ReachMap:
    """Where the robot's wrist point can be: world positions over random joint configurations.

    The wrist point W is fixed in the end-effector frame and independent of the
    last joint (or the last two, when they intersect as on Fetch), so a target
    pose fixes where W must be. A target whose W is farther than a margin from
    every sampled W is out of reach; IK on it would fail slowly.
    """

    frame: str
    p_EW: np.ndarray  # wrist point in the end-effector frame
    tree: cKDTree

    def wrist(self, X_WT: np.ndarray) -> np.ndarray:
        return X_WT[:3, :3] @ self.p_EW + X_WT[:3, 3]

    def plausible(self, X_WT: np.ndarray, margin: float) -> bool:
        distance, _ = self.tree.query(self.wrist(X_WT))
        return bool(distance <= margin)


def reach_key(world, frame: str) -> tuple:
    """What a reach map depends on: the model, its base weld, the planned coordinates
    (names, limits, wrapping), the held positions and the frame."""
    robot, space = world.scene.robot, world.space
    base = robot.base.pose() if robot.base is not None else None
    return (robot.model, robot.base_link, base, space.names, tuple(space.lower), tuple(space.upper), tuple(space.wrap),
            tuple(world.q_full), frame)


def reach_map(world, frame: str) -> ReachMap:
    """The reach map of ``frame`` in ``world``, cached by :func:`reach_key` (at most REACH_CACHE_SIZE kept)."""
    key = reach_key(world, frame)
    if key in _REACH_MAPS:
        _REACH_MAPS.move_to_end(key)
        return _REACH_MAPS[key]
    _REACH_MAPS[key] = m = _build_reach_map(world, frame)
    while len(_REACH_MAPS) > REACH_CACHE_SIZE:
        _REACH_MAPS.popitem(last=False)
    return m


def _build_reach_map(world, frame: str) -> ReachMap:
    kin = world.kinematics
    E = kin.frame(frame)
    X_WE = kin.X_WF(E, world.q_full)
    joints = _joints_to_root(kin.plant, E.body())
    # W: the child-side origin of the last movable joint; one joint further up while
    # that joint's origin lies on the axis of the joint below it (a spherical-ish wrist).
    W = joints[0].frame_on_child() if joints else E
    for below, above in zip(joints, joints[1:]):
        if not isinstance(below, RevoluteJoint):
            break
        X_Wb = kin.X_WF(below.frame_on_child(), world.q_full)
        axis = X_Wb.rotation() @ below.revolute_axis()
        o = kin.X_WF(above.frame_on_child(), world.q_full).translation()
        r = o - X_Wb.translation()
        if np.linalg.norm(r - axis * (r @ axis)) > 1e-6:
            break
        W = above.frame_on_child()
    p_EW = X_WE.inverse() @ kin.X_WF(W, world.q_full).translation()
    rng = np.random.default_rng(REACH_SEED)
    qs = np.tile(world.q_full, (REACH_SAMPLES, 1))
    space = world.space  # as REACH_SAMPLES calls of space.sample(rng): the same draws, in one call
    qs[:, world.planned] = space.lower + rng.random((REACH_SAMPLES, space.dim)) * (space.upper - space.lower)
    try:  # all samples in one batch (~50x faster than asking the plant one by one)
        chain = chain_to_frame(kin.plant, W)
        points = chain.forward(qs[:, chain.index])[:, :3, 3]
    except ValueError:  # a joint the chain cannot express (e.g. a planar base): ask the plant
        points = np.array([kin.X_WF(W, q).translation() for q in qs])
    return ReachMap(frame, np.asarray(p_EW), cKDTree(points))


def _joints_to_root(plant, body) -> list:
    """Movable joints from ``body`` up to the world, nearest first."""
    return [j for j in joints_to_world(plant, body) if j.num_positions() > 0]
