"""Several objects, one pick and place after another (issue #30): "put all the cups on the table".

The grounding's groups (:class:`grounding.model.Group`) say which objects may serve and how many.
Each step runs the pick-and-place task (:mod:`lazyground.tasks.place`) over the candidates still
left, so the planner chooses lazily which object and which placement come next (reward-penalty
over every candidate's grasp regions, then over the placement regions), with that task's fallback
to another object. After a step the scene changes: the object stands where it was released (an
obstacle from then on) and the robot starts the next step where the last one ended. Objects already
where the request asks are reported and not moved. What cannot be done ends the run with a partial
status (every object's record in ``Outcome.objects``), a planning failure (exit 1).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from grounding.model import Grounding
from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.planning.stop import Clock, StopCondition
from lazyground.scene.schema import PoseSpec, Scene
from lazyground.settings import RunSettings
from lazyground.tasks import place
from lazyground.tasks.outcome import ObjectStep, Outcome
from lazyground.tasks.worlds import Worlds


def moved(scene: Scene, object_id: str, X_WO, q_end: np.ndarray, names: tuple[str, ...]) -> Scene:
    """``scene`` after a placement: the object at ``X_WO``, the robot starting at ``q_end``."""
    pose = PoseSpec(tuple(float(x) for x in X_WO.xyz), tuple(float(x) for x in X_WO.rpy))
    objects = tuple(replace(o, pose=pose) if o.id == object_id else o for o in scene.objects)
    start = {**(scene.robot.start or {}), **{n: float(v) for n, v in zip(names, q_end)}}
    return replace(scene, objects=objects, robot=replace(scene.robot, start=start))


def run(scene: Scene, g: Grounding, settings: RunSettings, rng: np.random.Generator, worlds: Worlds, *,
        seed: int | None = None, keep_tree: bool = False, clock: Clock | None = None) -> Outcome:
    """Plan one pick and place per object the grounding's groups ask for, in turn.

    Args:
        scene, g, settings, rng, worlds, seed, keep_tree, clock: as every task's (:mod:`lazyground.tasks`);
            the planner's ``time_limit`` bounds the whole run, each step getting an equal share of what is left.

    Returns:
        An Outcome: every step's pick and place steps in order, the path through all of them, and
        ``objects``: per object asked for, done / already there / not done and why.
    """
    planner = settings.planner
    stop = StopCondition.after(planner.time_limit, clock=clock)
    current, placed = scene, []
    records: list[ObjectStep] = []
    outcomes: list[Outcome] = []
    notes: list[str] = []
    failure: PlanResult | None = None
    names, start = worlds.get().space.names, worlds.get().start
    for group in g.groups:
        for o in group.already:
            records.append(ObjectStep(o, "already there", _support(g, o), "not moved"))
        need = (len(group.objects) if group.count is None else group.count) - len(group.already)
        left = [o for o in group.objects if o not in group.already and o not in placed]
        while need > 0:
            remaining = stop.remaining()
            if not left or remaining <= 0:
                why = "no candidate left" if not left else "no time left"
                records += [ObjectStep(None, "not done", None, f"{group.phrase}: {why}")] * need
                failure = failure or _failed(seed, PlanStatus.TIMEOUT if left else PlanStatus.NO_VALID_GOAL, why)
                break
            sub = Grounding(g.request, "place", tuple(i for i in g.interpretations if i.objects[0] in left), g.notes)
            step_worlds = worlds if current is scene else Worlds(current, visual=worlds.visual)
            share = settings.replace(time_limit=min(remaining / _steps_left(g, group, need, placed), remaining))
            out = place.run(current, sub, share, rng, step_worlds, seed=seed, keep_tree=keep_tree, clock=clock)
            if step_worlds is not worlds:
                worlds.setup_s += step_worlds.setup_s
            notes += out.notes
            if not out.result.solved:
                why = f"{group.phrase}: {out.result.message}"
                records += [ObjectStep(None, "not done", None, why)] * need
                failure = failure or out.result
                break
            obj = out.picked
            others = [o for o in left if o != obj]
            records.append(ObjectStep(obj, "done", out.placement.target,
                                      f"chosen among {', '.join(left)}" if others else ""))
            outcomes.append(out)
            current = moved(current, obj, out.placement.X_WO, out.result.path[-1], names)
            placed.append(obj)
            left.remove(obj)
            need -= 1
    return _outcome(outcomes, records, notes, failure, names, start, seed, stop)


def _steps_left(g: Grounding, group, need: int, placed: list[str]) -> int:
    """Steps still to plan: this group's ``need`` and every later group's."""
    later = g.groups[g.groups.index(group) + 1:]
    return need + sum((len(x.objects) if x.count is None else x.count) - len(x.already) for x in later)


def _support(g: Grounding, object_id: str) -> str | None:
    """A target of ``object_id``'s interpretations (where it already rests, for the report)."""
    return next((i.target for i in g.interpretations if i.objects[0] == object_id), None)


def _failed(seed, status: PlanStatus, message: str) -> PlanResult:
    return PlanResult(status, seed, None, None, None, 0, 0, [], 0, 0.0, 0.0, 0.0, message)


def _outcome(outcomes: list[Outcome], records: list[ObjectStep], notes: list[str], failure: PlanResult | None,
             names, start: np.ndarray, seed, stop: StopCondition) -> Outcome:
    done = [r for r in records if r.status == "done"]
    already = [r for r in records if r.status == "already there"]
    missing = [r for r in records if r.status == "not done"]
    summary = (f"done: {', '.join(f'{r.object} -> {r.target}' for r in done) or 'none'}"
               + (f"; already there: {', '.join(r.object for r in already)}" if already else "")
               + (f"; not done: {len(missing)} ({missing[0].why})" if missing else ""))
    status = PlanStatus.SOLVED if not missing else failure.status if failure.status is not PlanStatus.SOLVED else PlanStatus.NO_VALID_GOAL
    steps = tuple(s for o in outcomes for s in o.steps)
    results = [o.result for o in outcomes]
    if results:
        path = np.vstack([results[0].path] + [r.path[1:] for r in results[1:]])
        last = results[-1]
        combined = place.combine(results, status, path, last.goal, last.goal_region, sum(r.time_s for r in results),
                                 summary if missing else "")
    else:
        combined = replace(failure or _failed(seed, status, summary), status=status, message=summary,
                           time_s=stop.elapsed(), path=None if missing else np.array([start]))  # nothing to move
    last = outcomes[-1] if outcomes else None
    return Outcome(combined, steps, names, tuple(notes) + (summary,), last.lift if last else None,
                   last.placement if last else None, sum(o.fallbacks for o in outcomes), objects=tuple(records))


def validate_several(outcome: Outcome, scene: Scene, resolution: float) -> list[str]:
    """Re-check every pick and place of a several-object outcome at ``resolution``, replaying the scene:
    each pick in the scene as the earlier steps left it (placed objects are obstacles), each place with
    the object attached; returns the problems found."""
    from lazyground.planning.rrt import path_is_valid

    problems, current = [], scene
    for pick, put in zip(outcome.steps[0::2], outcome.steps[1::2]):
        worlds = Worlds(current, visual=False)
        world, carrying = worlds.get(), worlds.get(put.grasp)
        if not np.allclose(pick.result.path[0], world.start, atol=1e-9):
            problems.append(f"{pick.label} does not start where the last step ended")
        if path_is_valid(world.space, world, pick.result.path, resolution) >= 0:
            problems.append(f"{pick.label} collides")
        if path_is_valid(carrying.space, carrying, put.result.path, resolution) >= 0:
            problems.append(f"{put.label} collides (with the carried object)")
        q_end = put.result.path[-1]
        X_WO = carrying.frame_pose(put.grasp.frame, q_end).compose(put.grasp.X_GO)
        current = moved(current, put.grasp.object_id, X_WO, q_end, world.space.names)
    return problems
