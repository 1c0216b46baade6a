"""Pick and place, grounded lazily across both steps ("put a cup on the table").

Step 1 plans from the start to a grasp of *any* object matching the request
(reward-penalty over all their grasp regions). The chosen object is then
attached to the gripper at the grasp it was reached with: its collision
geometry rides on the gripper body (contacts with the fingers are filtered as
adjacent bodies; everything else is checked, including the surface it came
from). A short lift-off follows, then step 2 plans to a placement region on
any matching surface. If the object cannot be placed within
``place_share * time_limit``, the planner goes back, excludes that object and
plans step 1 again over the others; the report says so.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from grounding.model import Grounding
from lazyground.drake.world import DrakeWorld
from lazyground.geometry import Pose
from lazyground.goals import goal_source_for
from lazyground.motion.steps import pick_and_place_motions
from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.planning.rrt import path_is_valid, solve
from lazyground.planning.stop import Clock, StopCondition
from lazyground.regions import GoalRegion
from lazyground.robots.end_effector import frame_of
from lazyground.scene.schema import Scene
from lazyground.settings import RunSettings, TaskSettings
from lazyground.tasks.anytime import best_step, improvement_notes
from lazyground.tasks.outcome import Grasp, Lift, Outcome, Placement, Step
from lazyground.tasks.worlds import Worlds

PICK_FAILED = "pick: "  # a failed outcome's message starts so when no candidate could be picked (no placement tried)


def _regions_by_object(g: Grounding) -> tuple[list[GoalRegion], dict[str, list[GoalRegion]]]:
    """All grasp regions (each once) and, per object, the placement regions of its targets."""
    grasps: dict[str, GoalRegion] = {}
    places: dict[str, dict[str, GoalRegion]] = {}
    for interp in g.interpretations:
        for r in interp.goal_regions:
            grasps.setdefault(r.id, r)
        for obj in interp.objects:
            for r in interp.place_regions:
                places.setdefault(obj, {}).setdefault(r.id, r)
    return list(grasps.values()), {k: list(v.values()) for k, v in places.items()}


def _placement_regions(regions: list[GoalRegion], half_height: float) -> tuple[GoalRegion, ...]:
    """Placement regions bound the carried object's bottom centre; the IK target is its centre."""
    return tuple(replace(r, X_SE=Pose((0.0, 0.0, half_height))) for r in regions)


def lift_off(world: DrakeWorld, carrying: DrakeWorld, ik, frame: str, q_grasp: np.ndarray, resolution: float,
             task: TaskSettings = TaskSettings()) -> Lift | None:
    """Raise the gripper (and object) straight up until the carried object is clear of its support.

    ``ik`` is the goal source registered for pose regions (it solves IK to a pose: ``ik.solve``).
    The lift is solved in ``task.lift_step`` IK steps (1 cm), each seeded by the last, so the path
    stays close to a vertical line. The object rests on its support at the
    grasp, so the first millimetres may touch it; from the first collision-free
    configuration on, the whole lift must be free. It stops at the first height
    of at least ``task.lift_min`` where the carried object is clear, and gives up above ``task.lift_max``.
    """
    X_WG = world.frame_pose(frame, q_grasp)
    path = [np.asarray(q_grasp, float)]
    q_full = world.full(q_grasp)
    for k in range(1, int(round(task.lift_max / task.lift_step)) + 1):
        h = k * task.lift_step
        target = Pose((X_WG.xyz[0], X_WG.xyz[1], X_WG.xyz[2] + h), X_WG.rpy)
        q_full = ik.solve(frame, target, q_full)
        if q_full is None:
            return None
        path.append(q_full[world.planned])
        if h < task.lift_min - 1e-9 or not carrying.config_free(path[-1]):
            continue
        if lift_is_clear(world, carrying, np.array(path), resolution):
            return Lift(np.array(path), h)
    return None


def lift_is_clear(world: DrakeWorld, carrying: DrakeWorld, lift: np.ndarray, resolution: float) -> bool:
    """The robot alone is free all along the lift; the carried object from its first free configuration on."""
    dense = np.vstack([carrying.space.discretize(a, b, resolution) for a, b in zip(lift[:-1], lift[1:])])
    free = carrying.configs_free(dense)
    return bool(free[-1] and np.all(free[int(np.argmax(free)):]) and np.all(world.configs_free(dense)))


def combine(results: list[PlanResult], status: PlanStatus, path, goal, region, elapsed: float, message: str) -> PlanResult:
    """One result for several steps: the last one's fields, the counts and lengths summed, the given status and path."""
    last = results[-1]
    return replace(
        last,
        status=status,
        path=path,
        goal=goal,
        goal_region=region,
        iterations=sum(r.iterations for r in results),
        tree_size=sum(r.tree_size for r in results),
        resamplings=sum(r.resamplings for r in results),
        time_s=elapsed,
        goal_sampling_s=sum(r.goal_sampling_s for r in results),
        collision_s=sum(r.collision_s for r in results),
        message=message,
        path_length=sum(r.path_length for r in results),
        invalid_paths_rejected=sum(r.invalid_paths_rejected for r in results),
    )


def run(scene: Scene, g: Grounding, settings: RunSettings, rng: np.random.Generator, worlds: Worlds, *,
        seed: int | None = None, keep_tree: bool = False, place_share: float | None = None,
        clock: Clock | None = None, prefer=None, spent: float = 0.0) -> Outcome:
    """Plan "put X on Y": a grasp of any X, then a placement on any Y, with fallback (the "place" task);
    then each step is shortened and timed (lazyground.motion.steps).

    Args:
        scene: the Scene.
        g: the grounding (action "place": grasp regions and per-object placement regions).
        settings: the run's RunSettings; the planner's ``time_limit`` bounds both steps and every fallback.
        rng: the only source of randomness.
        worlds: the scene's worlds (the caller's prebuilt world is used for the pick).
        seed: recorded in the results.
        keep_tree: keep the search trees (for viewers).
        place_share: the share of the time limit one placement attempt may use (default: the task setting's).
        clock: the clock the time limit is read on (default: the stop condition's).
        spent: seconds of the time limit used before the task (grounding), taken off its deadline.
        prefer: ``prefer(object_id, placement_regions)`` -> which placements to try first and which to rule out
            (a :class:`lazyground.tasks.packing.Preference`, several objects); None: uniform placements.

    Returns:
        An Outcome: on success the pick and the place step (the place step carries the
        object with its Grasp), the lift and the placement; otherwise no steps and why.
        Its result's ``time_s`` counts planning (IK, lift, search), not building worlds.
    """
    world = worlds.get()
    # one budget for every step: the pick gets what is left, a placement attempt its share (StopCondition.share)
    planner = settings.planner
    place_share = settings.task.place_share if place_share is None else place_share
    stop = StopCondition.after(planner.time_limit, max_iterations=planner.max_iterations, clock=clock, spent=spent)
    setup_before = worlds.setup_s  # world building from here on is set-up, not planning
    frame = frame_of(scene.robot)
    grasps, places = _regions_by_object(g)
    excluded: list[str] = []
    notes: list[str] = list(world.model_notes)
    results: list[PlanResult] = []

    motion_s = 0.0  # shortening and timing the steps after the solve (lazyground.motion): not planning

    def planning_s() -> float:
        return stop.elapsed() - (worlds.setup_s - setup_before) - motion_s

    def finish(status: PlanStatus, message: str, **done) -> Outcome:
        if results:
            combined = combine(results, status, done.get("path"), done.get("goal"), done.get("region"), planning_s(), message)
        else:
            combined = PlanResult(status, seed, None, None, None, 0, 0, [], 0, planning_s(), 0.0, 0.0, message)
        return Outcome(combined, done.get("steps", ()), world.space.names, tuple(notes), done.get("lift"),
                       done.get("placement"), len(excluded) if done.get("steps") else 0)

    while True:
        candidates = [r for r in grasps if r.object not in excluded]
        if stop.remaining() <= 0 or not candidates:
            break
        pick = best_step(lambda source, within, setup_s: solve(world.space, world, source, world.start, planner, rng,
                                                               seed=seed, keep_tree=keep_tree, stop=within, setup_s=setup_s),
                         lambda rs: goal_source_for(rs, world, settings.goal_sampling), tuple(candidates), world.space,
                         world, world.start, planner, stop.share(), rng)
        notes += [f"pick: {n}" for n in improvement_notes(pick)]
        pick = pick.result
        results.append(pick)
        if not pick.solved:
            return finish(pick.status, f"{PICK_FAILED}{pick.message}")
        if stop.timed_out():  # grasped at the limit: no time to lift and place (timeout)
            break
        obj = scene.object(pick.goal_region.object)
        q_grasp = pick.path[-1]
        X_WG = world.frame_pose(frame, q_grasp)
        grasp = Grasp(obj.id, pick.goal_region.id, pick.goal_region.label, frame, X_WG, X_WG.inverse().compose(obj.pose.pose()))
        built = worlds.setup_s
        carrying = worlds.get(grasp)
        setup = worlds.setup_s - built
        targets = _placement_regions(places.get(obj.id, []), obj.geometry.half_extents()[2])
        if not targets:
            notes.append(f"picked {obj.id} but it has no placement region; trying another object")
            excluded.append(obj.id)
            continue
        source = goal_source_for(targets, carrying, settings.goal_sampling)
        if prefer is not None:
            source.prefer = prefer(obj.id, targets)
        lift = lift_off(world, carrying, source, frame, q_grasp, planner.resolution, settings.task)
        if lift is None:
            notes.append(f"picked {obj.id} ({pick.goal_region.label}) but could not lift it clear; trying another object")
            excluded.append(obj.id)
            continue
        share = stop.share(place_share)
        budget = share.budget
        if budget <= 0:  # the lift used up the time: a timeout, not a reason to try another object
            break

        def placements(rs, q_lift=lift.q_lift, spare=[source], obj_id=obj.id):
            if spare and rs == targets:
                made = spare.pop()
            else:  # shortest / fastest: more searches and draws over some of the targets
                made = goal_source_for(rs, carrying, settings.goal_sampling)
                if prefer is not None:
                    made.prefer = prefer(obj_id, rs)
            made.near = q_lift  # placements prefer the configuration nearest where the place step starts
            return made

        place = best_step(lambda source, within, setup_s: solve(carrying.space, carrying, source, lift.q_lift, planner,
                                                                rng, seed=seed, keep_tree=keep_tree, stop=within,
                                                                setup_s=setup_s),
                          placements, targets, carrying.space, carrying, lift.q_lift, planner, share, rng)
        notes += [f"place: {n}" for n in improvement_notes(place)]
        place = place.result
        results.append(place)
        if place.status is PlanStatus.INTERRUPTED:  # Ctrl-C is not a reason to try another object
            return finish(place.status, f"place: {place.message}")
        if not place.solved:
            notes.append(f"picked {obj.id} but could not place it within {budget:.1f} s ({place.status.value}); "
                         "went back for another object")
            excluded.append(obj.id)
            continue
        X_WO = carrying.frame_pose(frame, place.path[-1]).compose(grasp.X_GO)
        t_motion = stop.now()
        pick, pick_motion, place, place_motion = pick_and_place_motions(world, carrying, pick, lift.path, place, settings, rng)
        motion_s = stop.now() - t_motion
        results[-2:] = [pick, place]  # the shortened steps (the combined result sums their lengths)
        placement = Placement(place.goal_region.id, place.goal_region.object, X_WO)
        steps = (Step(f"pick {obj.id}", pick, setup_before, motion=pick_motion),
                 Step(f"place {obj.id}", place, setup, grasp, motion=place_motion, placement=placement, lift=lift))
        chosen = next(i for i in g.interpretations if i.objects == (obj.id,) and i.target == place.goal_region.object)
        region = replace(place.goal_region, interpretation=chosen.id)  # placement regions are shared by interpretations
        return finish(PlanStatus.SOLVED, "", steps=steps, lift=lift, region=region, goal=place.goal,
                      path=np.vstack([pick.path, lift.path[1:], place.path[1:]]), placement=placement)
    if not results:
        return finish(PlanStatus.TIMEOUT, "no time left")
    tried = ", ".join(excluded) or "none"
    status = PlanStatus.TIMEOUT if stop.remaining() <= 0 else PlanStatus.NO_VALID_GOAL
    return finish(status, f"no object could be picked and placed in time (tried: {tried})")


def validate_pick_and_place(report, scene: Scene, resolution: float) -> list[str]:
    """Re-check both steps of a solved place ``PlanReport`` at ``resolution``, the carried object included; returns problems found."""
    problems = []
    pick, place = report.steps
    worlds = Worlds(scene, visual=False)
    world = worlds.get()
    if path_is_valid(world.space, world, pick.result.path, resolution) >= 0:
        problems.append("pick path collides")
    carrying = worlds.get(place.grasp)
    if path_is_valid(carrying.space, carrying, place.result.path, resolution) >= 0:
        problems.append("place path collides (with the carried object)")
    if not lift_is_clear(world, carrying, report.outcome.lift.path, resolution):
        problems.append("lift-off collides after leaving the support")
    return problems
