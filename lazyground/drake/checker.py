"""Drake's ``SceneGraphCollisionChecker`` behind the planner's ValidityChecker protocol.

One :class:`DrakeChecker` checks edges at one resolution, fixed once: at
construction, or (when built without one) by its first edge check. Drake's
edge step size is never rewritten afterwards; a caller that needs another
resolution asks :class:`lazyground.drake.world.DrakeWorld`, which keeps one
checker per resolution.
"""

from __future__ import annotations

import time

import numpy as np
from pydrake.planning import LinearDistanceAndInterpolationProvider, SceneGraphCollisionChecker

from lazyground.drake.coordinates import Coordinates

# Drake needs a positive step at construction; a checker built without a resolution
# replaces this once, before its first edge check, and never again.
_UNSET_STEP = 0.05


class DrakeChecker:
    """Config and edge checks over planned coordinates, in C++.

    Args:
        diagram: the scene's RobotDiagram (the checker takes ownership).
        robot: the robot's ModelInstanceIndex.
        coordinates: the planned coordinates (for ``full`` and the metric weights).
        padding: collision padding in metres, against the environment and the robot itself.
        edge_resolution: spacing of edge checks in the planner's weighted metric;
            None fixes it at the first edge check.
    """

    def __init__(self, diagram, robot, coordinates: Coordinates, padding: float, edge_resolution: float | None = None):
        self.coordinates = coordinates
        self.padding = padding
        self._resolution = edge_resolution
        # Drake's edge checks step in the same weighted metric as ours (fixed coordinates weigh 0).
        self.drake = SceneGraphCollisionChecker(
            model=diagram,
            robot_model_instances=[robot],
            distance_and_interpolation_provider=LinearDistanceAndInterpolationProvider(diagram.plant(), coordinates.plant_weights()),
            edge_step_size=_UNSET_STEP if edge_resolution is None else edge_resolution,
            env_collision_padding=padding,
            self_collision_padding=padding,
        )
        self.check_time = 0.0
        self.checks = 0

    @property
    def edge_resolution(self) -> float | None:
        """The fixed edge-check spacing (None until the first edge check of a checker built without one)."""
        return self._resolution

    def accepts(self, resolution: float) -> bool:
        """Whether edges at ``resolution`` can be checked here (the fixed one, or none fixed yet)."""
        return self._resolution is None or self._resolution == resolution

    def config_free(self, q: np.ndarray) -> bool:
        t0 = time.perf_counter()
        free = self.drake.CheckConfigCollisionFree(self.coordinates.full(q))
        self.check_time += time.perf_counter() - t0
        self.checks += 1
        return bool(free)

    def configs_free(self, qs: np.ndarray) -> np.ndarray:
        qs = np.atleast_2d(qs)
        if len(qs) == 1:
            return np.array([self.config_free(qs[0])])
        t0 = time.perf_counter()
        free = self.drake.CheckConfigsCollisionFree(list(self.coordinates.full(qs)), parallelize=False)
        self.check_time += time.perf_counter() - t0
        self.checks += len(qs)
        return np.asarray(free, bool)

    def edge_free(self, a: np.ndarray, b: np.ndarray, resolution: float) -> bool:
        """Whether the motion a → b is free, checked in C++ every ``resolution`` with early exit.

        Drake interpolates linearly, so b is first unwrapped onto the shorter arc
        from a (an angle of 3.5 rad is the same pose as -2.78 rad). Drake's
        weighted metric counts an angle step w·|dθ|, never less than our chord,
        so its steps are at least as fine as ``resolution`` in our metric.

        Raises:
            ValueError: ``resolution`` is not this checker's fixed resolution.
        """
        return bool(self._edge(self.drake.CheckEdgeCollisionFree, a, b, resolution))

    def edge_fraction(self, a: np.ndarray, b: np.ndarray, resolution: float) -> float:
        """The largest t in [0, 1] with a → a + t (b - a) free at ``resolution`` (1: all free; 0: blocked at once).

        Drake's ``MeasureEdgeCollisionFree``: the last free check before the first
        collision, as OMPL's ``checkMotion(s1, s2, lastValid)``.

        Raises:
            ValueError: ``resolution`` is not this checker's fixed resolution.
        """
        measure = self._edge(self.drake.MeasureEdgeCollisionFree, a, b, resolution)
        return max(0.0, measure.alpha_or(0.0))

    def _edge(self, check, a, b, resolution: float):
        if self._resolution is None:
            self.drake.set_edge_step_size(resolution)  # the one time: fixes this checker's resolution
            self._resolution = resolution
        elif resolution != self._resolution:
            raise ValueError(f"this collision checker checks edges every {self._resolution:g}, not {resolution:g}")
        t0 = time.perf_counter()
        a = np.asarray(a, float)
        out = check(self.coordinates.full(a), self.coordinates.full(a + self.coordinates.space.difference(a, b)))
        self.check_time += time.perf_counter() - t0
        self.checks += 1
        return out

    def colliding_pairs(self, q: np.ndarray) -> list[tuple[str, str]]:
        """Names of the geometry pairs within the padding at ``q``, sorted."""
        self.drake.UpdatePositions(self.coordinates.full(q))
        plant = self.drake.plant()
        sg = self.drake.model().scene_graph()
        sg_ctx = sg.GetMyContextFromRoot(self.drake.model_context().model_context())
        query = sg.get_query_output_port().Eval(sg_ctx)
        inspector = query.inspector()
        pairs = []
        for p in query.ComputeSignedDistancePairwiseClosestPoints(max_distance=self.padding + 1e-9):
            if p.distance > self.padding:
                continue
            pairs.append((_geometry_name(plant, inspector, p.id_A), _geometry_name(plant, inspector, p.id_B)))
        return sorted(set(pairs))


def _geometry_name(plant, inspector, gid) -> str:
    body = plant.GetBodyFromFrameId(inspector.GetFrameId(gid))
    if body is None or body.index() == plant.world_body().index():
        return inspector.GetName(gid).split("::")[-1]
    return body.name()
