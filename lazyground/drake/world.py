"""The scene in Drake: a thin facade over the diagram, coordinates, collision checker and kinematics.

With visualisation, :mod:`lazyground.drake` is the only place pydrake is
imported. At its edge everything becomes numpy arrays over the *planned*
coordinates. Each job lives in its own module:

* :mod:`lazyground.drake.diagram` — scene → RobotDiagram (environment, carried object);
* :mod:`lazyground.drake.coordinates` — the planned coordinates (names, limits, wrapping, metric, start);
* :mod:`lazyground.drake.checker` — collision checks, edge resolution fixed per checker;
* :mod:`lazyground.drake.kinematics` — forward kinematics.
"""

from __future__ import annotations

from collections import OrderedDict

import numpy as np

from lazyground.drake.checker import DrakeChecker
from lazyground.drake.coordinates import coordinates_from_plant
from lazyground.drake.diagram import Attachment, build_diagram, drake_shape, rigid_transform  # noqa: F401  (re-exported)
from lazyground.drake.kinematics import Kinematics
from lazyground.geometry import Pose
from lazyground.scene.schema import Scene

MAX_EXTRA_CHECKERS = 3  # other edge resolutions kept at once (each holds its own diagram)


class DrakeWorld:
    """The scene in Drake, with config checks over the planned coordinates.

    Args:
        scene: the loaded scene.
        padding: collision padding in metres (default: the scene's planner setting).
        attached: an object carried by the robot (removed from the environment).
        visual: also register visual geometry (for Meshcat).
        extend_builder: called with the RobotDiagramBuilder just before Build()
            (e.g. to add a MeshcatVisualizer to the diagram).
        edge_resolution: the spacing of edge checks; None fixes it at the first
            edge check. Edge checks at another resolution go to a second checker
            over a second diagram, built once per resolution (at most
            MAX_EXTRA_CHECKERS kept).

    Raises:
        SceneError: when the model cannot be parsed or the start is invalid for it.
    """

    def __init__(self, scene: Scene, padding: float | None = None, attached: Attachment | None = None, visual: bool = True,
                 extend_builder=None, edge_resolution: float | None = None):
        self.scene = scene
        self.attached = attached
        self.padding = scene.planner.collision_padding if padding is None else padding
        notes: list[str] = []
        mimic: list = []
        diagram, self.robot = build_diagram(scene, attached, visual, extend_builder, notes, mimic)
        self.model_notes = tuple(notes)  # what was done to the robot model that the scene did not say
        self.coordinates = coordinates_from_plant(diagram.plant(), self.robot, scene, tuple(mimic))
        self.checker = DrakeChecker(diagram, self.robot, self.coordinates, self.padding, edge_resolution)
        self.plant = self.checker.drake.plant()
        self.diagram = self.checker.drake.model()
        self.kinematics = Kinematics(self.plant, self.robot)
        self.space = self.coordinates.space
        self.planned = list(self.coordinates.planned)
        self.q_full = self.coordinates.q_full
        self.start = self.coordinates.start
        self._extra: OrderedDict[float, DrakeChecker] = OrderedDict()
        self._reach: list = []  # the reach prior, once built (lazyground.drake.reach_prior)

    def reach_prior(self):
        """The reach prior from the start, built on first use: a planar robot's (a car: its disc,
        :func:`lazyground.drake.reach_prior.planar_reach`), else an arm's (balls in its hand, grids built per
        ball as regions ask: :func:`lazyground.drake.arm_reach.arm_reach`); None for other robots."""
        if not self._reach:
            from lazyground.drake.arm_reach import arm_reach
            from lazyground.drake.reach_prior import planar_reach

            prior = planar_reach(self)
            self._reach.append(prior if prior is not None else arm_reach(self))
        return self._reach[0]

    # --- kinematics ------------------------------------------------------------------------
    def frame_pose(self, frame: str, q: np.ndarray) -> Pose:
        """World pose X_WF of a robot frame at planned coordinates ``q``."""
        return self.kinematics.pose(frame, self.full(q))

    def full(self, q: np.ndarray) -> np.ndarray:
        """The plant's position vector for planned coordinates ``q`` (rows or one vector)."""
        return self.coordinates.full(q)

    # --- ValidityChecker -------------------------------------------------------------------
    @property
    def check_time(self) -> float:
        return self.checker.check_time + sum(c.check_time for c in self._extra.values())

    @property
    def checks(self) -> int:
        return self.checker.checks + sum(c.checks for c in self._extra.values())

    def config_free(self, q: np.ndarray) -> bool:
        return self.checker.config_free(q)

    def config_unpadded_free(self, q: np.ndarray) -> bool:
        return self.checker.config_unpadded_free(q)

    def configs_free(self, qs: np.ndarray) -> np.ndarray:
        return self.checker.configs_free(qs)

    def configs_free_along(self, qs: np.ndarray) -> np.ndarray:
        """:meth:`configs_free` of configurations in sequence along a path (see :meth:`DrakeChecker.configs_free_along`)."""
        return self.checker.configs_free_along(qs)

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the motion a → b is free at ``resolution`` (see :meth:`DrakeChecker.edge_free`)."""
        checker = self.checker if self.checker.compiled is not None else self._checker_for(resolution)  # any resolution
        return checker.edge_free(a, b, resolution)

    @property
    def edge_part_free(self):
        """The checker's ordered, partial edge check (:meth:`DrakeChecker.edge_part_free`); None when it has no
        compiled certifier (a car's world: its edges go to Drake's batch checks)."""
        return self.checker.edge_part_free if self.checker.compiled is not None else None

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The free fraction of a → b at ``resolution`` (see :meth:`DrakeChecker.edge_fraction`)."""
        return self._checker_for(resolution).edge_fraction(a, b, resolution)

    def _checker_for(self, resolution: float) -> DrakeChecker:
        if self.checker.accepts(resolution):
            return self.checker
        if resolution in self._extra:
            self._extra.move_to_end(resolution)
            return self._extra[resolution]
        diagram, robot = build_diagram(self.scene, self.attached, visual=False)
        # only edge checks come here (batches go to self.checker): no certifier to build
        checker = DrakeChecker(diagram, robot, self.coordinates, self.padding, resolution, certify=False)
        self._extra[resolution] = checker
        if len(self._extra) > MAX_EXTRA_CHECKERS:
            old = self._extra.popitem(last=False)[1]  # keep its counts in the totals
            self.checker.check_time += old.check_time
            self.checker.checks += old.checks
        return checker

    def explain(self, q: np.ndarray) -> str:
        """The colliding pairs at q, e.g. "car_body collides with wall_1"."""
        pairs = self.colliding_pairs(q)
        if not pairs:
            return "no colliding pair found"
        shown = ", ".join(f"{a} collides with {b}" for a, b in pairs[:3])
        return shown + (f" (+{len(pairs) - 3} more)" if len(pairs) > 3 else "")

    def colliding_pairs(self, q: np.ndarray) -> list[tuple[str, str]]:
        """Names of the geometry pairs within the padding at ``q``, sorted."""
        return self.checker.colliding_pairs(q)
