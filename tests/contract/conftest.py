"""The implementations every contract suite runs against, built once per session.

Each interface test in this package is written once against the protocols of
:mod:`lazyground.planning.problem` and parametrised over every implementation,
as Drake's ``bindings/pydrake/planning/test`` reuses one interface test:

* collision checkers: the toy box world (``tests/unit/toy.py``) and ``DrakeWorld``
  on a parking scene (planar car, wrapping heading) and a Fetch scene (arm);
* goal sources: ``ConfigGoalSource`` (toy and parking) and ``IKGoalSource`` (Fetch);
* planners: ``solve`` with ``algorithm`` "rrt" and "bidirectional" on the toy world
  and on parking.

Drake-backed cases skip when pydrake is missing. Everything random comes from a
seeded generator; outcome tests bound the planner by ``max_iterations`` with a time
limit that is never reached (:data:`NO_CLOCK`), so a loaded machine gives the same answers.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

from lazyground.planning.problem import GoalSample, GoalSource, ValidityChecker
from lazyground.planning.space import ConfigSpace
from tests.unit import toy

NO_CLOCK = 1e6  # s: a time limit (and goal-sampling deadline) never reached; iterations bound every outcome
SCENES = Path(__file__).resolve().parents[2] / "yaml_scenes"
HAS_DRAKE = importlib.util.find_spec("pydrake") is not None
DRAKE = pytest.mark.skipif(not HAS_DRAKE, reason="pydrake is not installed")


@dataclass(frozen=True)
class World:
    """One implementation of the checker side, with what the contracts need to exercise it.

    ``goals(kind)`` builds a fresh goal source over "reachable" regions (some sample
    can be reached), "impossible" ones (no valid sample exists) or, where the world
    has one, "unreachable" ones (valid samples no path reaches).
    """

    name: str
    space: ConfigSpace
    checker: ValidityChecker
    start: np.ndarray
    resolution: float  # the scene's edge resolution
    step_size: float
    goals: Callable[[str], GoalSource]
    in_region: Callable[[GoalSource, GoalSample], bool]  # the sample's end lies in its region
    unreachable: bool = False  # whether goals("unreachable") exists


def _toy() -> World:
    world = toy.BoxWorld(toy.WALLS)
    kinds = {"reachable": [toy.UNREACHABLE, toy.INVALID, toy.REACHABLE], "impossible": [toy.INVALID],
             "unreachable": [toy.UNREACHABLE]}
    return World("toy", toy.SPACE, world, toy.START, 0.05, 0.5,
                 lambda kind: toy.goal_source(world, kinds[kind]),
                 lambda source, s: source.regions[s.region].contains(s.end), unreachable=True)


def _outside(region, space: ConfigSpace):
    """A copy of a C-space region moved wholly beyond the space's upper limits: no valid sample."""
    shift = np.where(space.wrap, 0.0, space.upper - space.lower + 10.0)
    return replace(region, id=f"{region.id}.outside", lower=tuple(np.add(region.lower, shift)),
                   upper=tuple(np.add(region.upper, shift)))


def _drake(scene_name: str, request: str) -> World:
    import grounding
    from lazyground.drake.world import DrakeWorld
    from lazyground.goals import ConfigGoalSource
    from lazyground.scene import load_scene

    scene = load_scene(SCENES / f"{scene_name}.yaml")
    world = DrakeWorld(scene)
    regions = tuple(grounding.ground(request, scene).goal_regions)
    step, resolution = scene.planner.step_size, scene.planner.edge_resolution or scene.planner.step_size / 10
    if regions[0].kind == "config":
        kinds = {"reachable": regions, "impossible": (_outside(regions[0], world.space),)}
        return World(scene_name, world.space, world, world.start, resolution, step,
                     lambda kind: ConfigGoalSource(kinds[kind], world.space, world),
                     lambda source, s: source.regions[s.region].contains(s.end))
    from lazyground.drake.ik import IKGoalSource, IKSettings, region_coordinates
    from lazyground.geometry import Pose

    settings = IKSettings(attempt_budget=None)  # attempts bounded by restarts, not by the clock
    far = replace(regions[0], id="far", X_WR=Pose((5.0, 0.0, 0.8), (0.0, np.pi / 2, 0.0)))  # 5 m away: out of reach
    kinds = {"reachable": regions, "impossible": (far,)}

    def in_region(source, s):
        region = source.regions[s.region]
        X_WE = source.frame_pose(region.frame, world.full(s.end))
        return region.contains(region_coordinates(region, X_WE), tol=0.01)  # within the IK tolerance

    return World(scene_name, world.space, world, world.start, resolution, step,
                 lambda kind: IKGoalSource(kinds[kind], world, settings), in_region)


BUILDERS = {
    "toy": _toy,
    "parking_1": lambda: _drake("parking_1", "park"),
    "fetch_cans_1": lambda: _drake("fetch_cans_1", "pick up a can"),
}
_BUILT: dict[str, World] = {}


def world_param(name: str):
    """A pytest parameter for one implementation (Drake ones marked to skip without pydrake)."""
    return pytest.param(name, id=name, marks=() if name == "toy" else (DRAKE,))


def get_world(name: str) -> World:
    """The implementation ``name``, built on first use and shared by every suite (Drake worlds are slow to build)."""
    if name not in _BUILT:
        _BUILT[name] = BUILDERS[name]()
    return _BUILT[name]


def colliding_config(w: World, rng: np.random.Generator) -> np.ndarray:
    """A configuration inside the limits that collides, found by seeded uniform sampling."""
    for _ in range(10_000):
        q = w.space.sample(rng)
        if not w.checker.config_free(q):
            return q
    raise AssertionError(f"{w.name}: no colliding configuration in 10,000 samples")


def free_edges(w: World, rng: np.random.Generator, n: int, length: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """n edges of at most ``length`` between free configurations that the checker calls free."""
    out = []
    for _ in range(100 * n):
        a = w.space.sample(rng)
        b, _ = w.space.steer(a, w.space.sample(rng), length)
        if w.checker.config_free(a) and w.checker.edge_free(a, b, w.resolution):
            out.append((a, b))
            if len(out) == n:
                return out
    raise AssertionError(f"{w.name}: found only {len(out)} free edges")


def blocked_edge(w: World, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """An edge from a free configuration to a colliding one."""
    b = colliding_config(w, rng)
    for _ in range(10_000):
        a = w.space.sample(rng)
        if w.checker.config_free(a):
            return a, b
    raise AssertionError(f"{w.name}: no free configuration in 10,000 samples")
