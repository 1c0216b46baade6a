"""IK solvers behind one protocol: rows of (target pose, start) in, rows of (answer, met) out.

* :class:`BatchSolver`: damped least squares on the chain (:mod:`lazyground.drake.ik.batch`),
  every row in one compiled call (~10 µs a solve); only for frames the chain expresses.
* :class:`ProgramSolver`: a Drake ``InverseKinematics`` program per solve, SNOPT (or IPOPT when
  SNOPT is not available), ~1.5 ms a solve; any frame (a planar or floating base too). No
  minimum-distance constraint: with one, failed solves cost 0.3-0.8 s each (issue 7);
  collisions are checked after.

Both judge an answer by forward kinematics against the accepted error of the tolerances
(:func:`lazyground.tolerance.accepted_error`), not by the solver's status.
"""

from __future__ import annotations

import weakref
from typing import Protocol

import numpy as np
from pydrake.math import RotationMatrix
from pydrake.multibody.inverse_kinematics import InverseKinematics
from pydrake.solvers import IpoptSolver, SnoptSolver, SolverOptions

from lazyground.drake import compiled
from lazyground.drake.arm_reach import end_effector_frame
from lazyground.drake.chain import REVOLUTE, chain_to_frame
from lazyground.drake.ik.batch import BatchIKProblem, solve_batch
from lazyground.drake.ik.settings import IKSettings
from lazyground.tolerance import accepted_error


class IKSolver(Protocol):
    """Solves IK for rows of targets from rows of starts (full plant positions)."""

    def solve(self, frame: str, targets: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(answers (N, plant positions), met (N,) bool) for targets X_WT (N, 4, 4) of ``frame`` from ``starts``."""
        ...


def pose_error(kinematics, frame: str, q_full: np.ndarray, X_WT: np.ndarray) -> tuple[float, float]:
    """(position error in m, rotation angle in rad) of ``frame`` at ``q_full`` from the pose X_WT (4x4)."""
    X = kinematics.matrix(frame, q_full)
    R = X_WT[:3, :3].T @ X[:3, :3]
    angle = float(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))
    return float(np.linalg.norm(X[:3, 3] - X_WT[:3, 3])), angle


class BatchSolver:
    """Every row in one damped-least-squares batch per call (an :class:`IKSolver`).

    Args:
        problems: the batch IK problem of every frame it solves (:func:`problem_for_frame`).
        settings: the tolerances; ``batch_iterations`` unless ``iterations`` is given.
        iterations: iterations per solve (pre-poses from their goal need few).
    """

    def __init__(self, problems: dict[str, BatchIKProblem], settings: IKSettings, iterations: int | None = None):
        compiled.warm_up()  # once per process, reported with the collision kernels (not a request's time)
        self.problems = problems
        self.settings = settings
        self.iterations = settings.batch_iterations if iterations is None else iterations

    def solve(self, frame: str, targets: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        s, problem = self.settings, self.problems[frame]
        index = problem.chain.index
        accepted = accepted_error(s.position_tolerance, s.orientation_tolerance)
        q, _, met = solve_batch(problem, starts[:, index], targets, s.position_tolerance, s.orientation_tolerance,
                                self.iterations, accepted)
        answers = starts.copy()
        answers[:, index] = q
        return answers, met


_PROBLEMS: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # world -> {(frame, full_turns): problem}


def problem_for_frame(world, frame: str, full_turns: bool = True) -> BatchIKProblem | None:
    """The chain to ``frame`` with its planned joints free, or None when the chain cannot express it.

    With ``full_turns`` a joint whose limits span a full turn wraps (IK may pass its seam);
    without, only the joints the planner's space wraps do. Built once per world and arguments
    (~5 ms a frame, against a goal source per plan; the problem is frozen and read only).
    """
    problems = _PROBLEMS.setdefault(world, {})
    key = (frame, full_turns)
    if key not in problems:
        problems[key] = _problem_for_frame(world, frame, full_turns)
    return problems[key]


def warm_problems(world) -> None:
    """Build the chain problems of ``world``'s end-effector frame now (set-up: they depend on the world and frame
    only; ~5 ms a world, #33), both as the IK source asks them (with and without full turns)."""
    frame = end_effector_frame(world)
    if frame is not None:
        for full_turns in (True, False):
            problem_for_frame(world, frame, full_turns)


def _problem_for_frame(world, frame: str, full_turns: bool) -> BatchIKProblem | None:
    try:
        chain = chain_to_frame(world.plant, world.plant.GetFrameByName(frame))
    except ValueError:  # e.g. a planar base: SNOPT on the plant instead
        return None
    column = {int(i): c for c, i in enumerate(world.planned)}
    free = np.array([int(i) in column for i in chain.index])
    space = world.space
    lower = np.array([space.lower[column[i]] if i in column else world.q_full[i] for i in chain.index], float)
    upper = np.array([space.upper[column[i]] if i in column else world.q_full[i] for i in chain.index], float)
    # a revolute joint whose limits span a full turn reaches every angle: IK may wrap it
    # (the answer stays within the limits), where clipping would leave it stuck at +-pi
    wrap = np.array([i in column and (bool(space.wrap[column[i]]) or (full_turns and kind == REVOLUTE and hi - lo >= 2 * np.pi - 1e-9))
                     for i, kind, lo, hi in zip(chain.index, chain.kinds, lower, upper)])
    return BatchIKProblem(chain, free, lower, upper, wrap)


class ProgramSolver:
    """One Drake ``InverseKinematics`` program per solve over the planned coordinates (an :class:`IKSolver`).

    Args:
        world: the DrakeWorld (its plant, kinematics, planned coordinates and their limits).
        settings: the tolerances, the solver (``batch`` and ``snopt`` take SNOPT when available)
            and its iteration limit.
    """

    def __init__(self, world, settings: IKSettings):
        self.settings = settings
        self._plant = world.plant
        self._kinematics = world.kinematics
        planned = np.asarray(world.planned, int)
        self._lower = world.q_full.copy()
        self._upper = world.q_full.copy()
        self._lower[planned] = world.space.lower
        self._upper[planned] = world.space.upper
        if settings.solver in ("batch", "snopt") and SnoptSolver().available() and SnoptSolver().enabled():
            self._solver = SnoptSolver()
            self._options = SolverOptions()
            self._options.SetOption(SnoptSolver.id(), "Major iterations limit", settings.major_iterations)
        else:
            self._solver = IpoptSolver()
            self._options = SolverOptions()
            self._options.SetOption(IpoptSolver.id(), "max_iter", 3 * settings.major_iterations)
            self._options.SetOption(IpoptSolver.id(), "print_level", 0)

    def solve(self, frame: str, targets: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        rows = [self.solve_pose(frame, X, q0) for X, q0 in zip(targets, starts)]
        answers = np.array([q0 if q is None else q for q, q0 in zip(rows, starts)])
        return answers, np.array([q is not None for q in rows], bool)

    def solve_pose(self, frame: str, X_WT: np.ndarray, seed_full: np.ndarray) -> np.ndarray | None:
        """Full plant positions putting ``frame`` at X_WT (4x4) within tolerance, from ``seed_full`` (clipped to the limits), or None."""
        s, plant = self.settings, self._plant
        ik = InverseKinematics(plant, with_joint_limits=False)
        q = ik.q()
        prog = ik.get_mutable_prog()
        prog.AddBoundingBoxConstraint(self._lower, self._upper, q)
        G = plant.GetFrameByName(frame)
        p_WT = X_WT[:3, 3]
        tol = np.full(3, s.position_tolerance)
        ik.AddPositionConstraint(G, np.zeros(3), plant.world_frame(), p_WT - tol, p_WT + tol)
        ik.AddOrientationConstraint(plant.world_frame(), RotationMatrix(X_WT[:3, :3]), G, RotationMatrix(), s.orientation_tolerance)
        result = self._solver.Solve(prog, np.clip(seed_full, self._lower, self._upper), self._options)
        q_sol = np.asarray(result.GetSolution(q), float)
        if not np.all(np.isfinite(q_sol)):
            return None
        dp, angle = pose_error(self._kinematics, frame, q_sol, X_WT)  # judged by forward kinematics, not the status
        max_dp, max_angle = accepted_error(s.position_tolerance, s.orientation_tolerance)
        return q_sol if dp <= max_dp and angle <= max_angle else None
