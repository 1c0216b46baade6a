"""The Python API: a scene and a text request in, a planned grounding out.

    from lazyground import api
    report = api.plan("yaml_scenes/parking_1.yaml", "park", seed=3)
    print(report.result.status, report.chosen_object)

Data flow: request → :func:`grounding.ground` → goal regions → goal source
(C-space sampling or Drake IK) → :func:`lazyground.planning.solve` → report.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, fields, replace
from pathlib import Path

import numpy as np

import grounding
from grounding.model import Grounding, Interpretation
from lazyground.planning.problem import PlannerSettings, PlanResult, PlanStatus
from lazyground.planning.rrt import solve
from lazyground.robots.car import planning_space
from lazyground.scene import Scene, load_scene


@dataclass(frozen=True)
class PlanReport:
    """One request planned on one scene: the grounding, the result and where the time went."""

    request: str
    scene: str
    seed: int
    settings: PlannerSettings
    grounding: Grounding
    result: PlanResult
    joint_names: tuple[str, ...]
    grounding_s: float
    setup_s: float  # building the Drake world
    steps: tuple["PlanReport", ...] = ()  # pick and place: the pick and the place step
    notes: tuple[str, ...] = ()
    extra: dict = field(default_factory=dict)

    @property
    def status(self) -> PlanStatus:
        return self.result.status

    @property
    def time_s(self) -> float:
        """Planning time as a user experiences it: grounding + goal sampling + search."""
        return self.grounding_s + self.result.time_s

    @property
    def chosen(self) -> Interpretation | None:
        region = self.result.goal_region
        if region is None:
            return None
        return next(i for i in self.grounding.interpretations if i.id == region.interpretation)

    @property
    def chosen_object(self) -> str | None:
        """The object acted on: the spot parked in, the object picked (also for pick and place)."""
        if "picked" in self.extra:
            return self.extra["picked"]
        return self.result.goal_region.object if self.result.goal_region else None


def planner_settings(scene: Scene, **overrides) -> PlannerSettings:
    """The scene's planner defaults, then its ``per_algorithm`` settings for the algorithm
    that will run, then the non-None ``overrides``."""
    spec = scene.planner
    base = PlannerSettings(
        strategy=spec.strategy,
        algorithm=spec.algorithm,
        goal_bias=spec.goal_bias,
        step_size=spec.step_size,
        edge_resolution=spec.edge_resolution,
        time_limit=spec.time_limit,
        max_iterations=spec.max_iterations,
        initial_goal_samples=spec.initial_goal_samples,
        resample_threshold=spec.resample_threshold,
        resample_count=spec.resample_count,
        goal_extension=spec.goal_extension,
        kinematics=spec.kinematics,
    )
    known = {f.name for f in fields(PlannerSettings)}
    unknown = set(overrides) - known
    if unknown:
        raise TypeError(f"unknown planner settings: {', '.join(sorted(unknown))}")
    per = spec.per_algorithm.get(overrides.get("algorithm") or spec.algorithm)
    if per is not None:
        base = replace(base, **{f.name: getattr(per, f.name) for f in fields(per) if getattr(per, f.name) is not None})
    return replace(base, **{k: v for k, v in overrides.items() if v is not None})


def make_goal_source(world, regions):
    """The goal sampler for these regions: C-space boxes directly, workspace regions by IK."""
    kinds = {r.kind for r in regions}
    if kinds == {"config"}:
        from lazyground.goals import ConfigGoalSource

        return ConfigGoalSource(regions, world.space, world)
    from lazyground.drake.ik import IKGoalSource

    return IKGoalSource(regions, world)


def plan(
    scene: Scene | str | Path,
    request: str,
    *,
    seed: int | None = None,
    keep_tree: bool = False,
    world=None,
    **overrides,
) -> PlanReport:
    """Ground ``request`` in ``scene`` and plan to whichever interpretation is reachable.

    Args:
        scene: a Scene or a path to a scene file.
        request: the text request, e.g. "park" or "pick up a can".
        seed: the random seed (default: the scene's); recorded in the report.
        keep_tree: keep the search tree in the result (for visualisation).
        world: a prebuilt DrakeWorld for this scene (saves set-up time in loops).
        **overrides: PlannerSettings fields (strategy, goal_bias, step_size, time_limit, ...).

    Raises:
        SceneError: the scene file is invalid.
        GroundingError: the request does not ground in the scene.
    """
    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    seed = scene.planner.seed if seed is None else int(seed)
    settings = planner_settings(scene, **overrides)
    t0 = time.perf_counter()
    g = grounding.ground(request, scene)
    grounding_s = time.perf_counter() - t0
    if g.action == "place":
        from lazyground.place import plan_pick_and_place

        return plan_pick_and_place(scene, g, settings, seed, grounding_s, keep_tree=keep_tree)
    t1 = time.perf_counter()
    if world is None:
        from lazyground.drake.world import DrakeWorld

        world = DrakeWorld(scene)
    setup_s = time.perf_counter() - t1
    rng = np.random.default_rng(seed)
    source = make_goal_source(world, g.goal_regions)
    space = planning_space(scene, world.space, settings.kinematics)
    result = solve(space, world, source, world.start, settings, rng, seed=seed, keep_tree=keep_tree)
    return PlanReport(
        request=request,
        scene=scene.name,
        seed=seed,
        settings=settings,
        grounding=g,
        result=result,
        joint_names=world.space.names,
        grounding_s=grounding_s,
        setup_s=setup_s,
    )
