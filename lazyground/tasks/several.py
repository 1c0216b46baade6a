"""Several objects, one pick and place after another (issue #30): "put all the cups on the table".

The grounding's groups (:class:`grounding.model.Group`) say which objects may serve and how many.
Each step runs the pick-and-place task (:mod:`lazyground.tasks.place`) over the candidates still
left, so the planner chooses lazily which object and which placement come next (reward-penalty
over every candidate's grasp regions, then over the placement regions), with that task's fallback
to another object. After a step the scene changes: the object stands where it was released (an
obstacle from then on) and the robot starts the next step where the last one ended. Objects already
where the request asks are reported and not moved.

* While objects follow, placements leave room for them (:mod:`lazyground.tasks.packing`).
* A step that finds no feasible choice sends the planner back: the step before it is re-planned
  with its placement ruled out, at most ``backtracks`` times a run (:class:`~lazyground.settings.TaskSettings`).
* "pick up two cans" (grounding action ``pick``): one gripper, so every object but the last is put
  down on a stow surface (status "stowed") and the last is picked and held ("held").

What cannot be done ends the run with a partial status (every object's record in
``Outcome.objects``), a planning failure (exit 1).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from grounding.model import Grounding
from lazyground.planning.problem import PlanResult, PlanStatus
from lazyground.planning.stop import Clock, StopCondition
from lazyground.robots.end_effector import frame_of
from lazyground.scene.schema import Scene
from lazyground.settings import RunSettings
from lazyground.tasks import packing, place, reach
from lazyground.tasks.outcome import Grasp, ObjectStep, Outcome
from lazyground.tasks.replay import moved, scenes_per_step
from lazyground.tasks.worlds import Worlds


@dataclass(frozen=True)
class _Done:
    """One planned step: the group it served, the object, its outcome and the scene after it."""

    group: int
    object: str
    outcome: Outcome
    after: Scene
    worlds: Worlds  # the worlds of ``after`` (reused when a backtrack returns to it)
    among: tuple[str, ...]  # the candidates it chose among


def run(scene: Scene, g: Grounding, settings: RunSettings, rng: np.random.Generator, worlds: Worlds, *,
        seed: int | None = None, keep_tree: bool = False, clock: Clock | None = None, spent: float = 0.0) -> Outcome:
    """Plan one pick and place per object the grounding's groups ask for, in turn.

    Args:
        scene, g, settings, rng, worlds, seed, keep_tree, clock, spent: as every task's (:mod:`lazyground.tasks`);
            the planner's ``time_limit`` bounds the whole run, each step getting an equal share of what is left.

    Returns:
        An Outcome: every step's pick and place steps in order, the path through all of them, and
        ``objects``: per object asked for, done / already there / stowed / held / not done and why.
    """
    stop = StopCondition.after(settings.planner.time_limit, clock=clock, spent=spent)
    picking = g.action == "pick"
    slots = [k for k, group in enumerate(g.groups) for _ in range(_need(group))]
    done: list[_Done] = []
    keep_clear: dict[int, list[tuple[float, float, float, float]]] = {}  # per step: placements a backtrack undid
    backtracks = settings.task.backtracks
    notes: list[str] = []
    failure: PlanResult | None = None
    names, start = worlds.get().space.names, worlds.get().start
    while len(done) < len(slots):
        k = len(done)
        current, step_worlds = (done[-1].after, done[-1].worlds) if done else (scene, worlds)
        group = g.groups[slots[k]]
        left = [o for o in group.objects if o not in group.already and o not in {d.object for d in done}]
        remaining = stop.remaining()
        if not left or remaining <= 0:
            why = "no candidate left" if not left else "no time left"
            failure = _failed(seed, PlanStatus.TIMEOUT if left else PlanStatus.NO_VALID_GOAL, f"{group.phrase}: {why}")
            break
        share = settings.replace(time_limit=remaining / (len(slots) - k))
        held = picking and k == len(slots) - 1
        setup = step_worlds.setup_s
        if held:
            out = _hold(current, g, left, share, rng, step_worlds, seed, keep_tree, clock)
        else:
            draws = settings.task.placement_draws if k < len(slots) - 1 else 1
            clear = tuple(keep_clear.get(k, ()))
            prefer = None if draws == 1 and not clear else (
                lambda obj, regions, current=current, clear=clear: packing.preference(current, obj, regions, draws, clear))
            sub = Grounding(g.request, "place", tuple(i for i in g.interpretations
                                                      if i.action == "place" and i.objects[0] in left), g.notes)
            out = place.run(current, sub, share, rng, step_worlds, seed=seed, keep_tree=keep_tree, clock=clock,
                            prefer=prefer)
        if step_worlds is not worlds:
            worlds.setup_s += step_worlds.setup_s - setup
        notes += [n for n in out.notes if n not in notes]
        if out.result.solved:
            obj = out.picked
            after = current if held else moved(current, obj, out.placement.X_WO, out.result.path[-1], names)
            done.append(_Done(slots[k], obj, out, after, step_worlds if held else Worlds(after, visual=worlds.visual),
                              tuple(left)))
            continue
        if (k > 0 and backtracks > 0 and stop.remaining() > 0 and out.result.status is not PlanStatus.INTERRUPTED
                and _may_have_blocked(done[-1], current, left, out, held)):
            backtracks -= 1
            notes.append(_go_back(done, keep_clear, k, group.phrase, out.result.message,
                                  f"{settings.task.backtracks - backtracks} of {settings.task.backtracks}"))
            continue
        failure = replace(out.result, message=f"{group.phrase}: {out.result.message}")
        break
    records = _records(g, done, slots, failure, picking)
    return _outcome(done, records, notes, failure, names, start, seed, stop,
                    settings.task.backtracks - backtracks)


def _go_back(done: list[_Done], keep_clear: dict, k: int, phrase: str, why: str, count: str) -> str:
    """Undo step ``k - 1`` (0-based ``k`` failed): its placement is kept clear when it is planned again; the note."""
    undone = done.pop()
    X = undone.outcome.placement.X_WO
    keep_clear.setdefault(k - 1, []).append((*X.xyz, packing.footprint(undone.after.object(undone.object))))
    for later in [s for s in keep_clear if s >= k]:
        del keep_clear[later]  # the scene they were ruled out in is gone
    return (f"step {k + 1} ({phrase}) found no feasible choice ({why}); went back to step {k}: {undone.object} is put "
            f"elsewhere than {undone.outcome.placement.target} at ({X.xyz[0]:.2f}, {X.xyz[1]:.2f}) (backtrack {count})")


BLOCK_RADIUS = 0.3  # m: a placed object farther than this from every candidate cannot have blocked their grasps


def _may_have_blocked(last: _Done, scene: Scene, left: list[str], out: Outcome, held: bool) -> bool:
    """Whether the last placement can be why this step failed, so going back may help.

    Not when no candidate could even be grasped (no valid goal configuration) and the placed object is farther
    than BLOCK_RADIUS from all of them: an object out of reach stays out of reach wherever the last one went
    (kitchen: cup_blue, beyond the arm on the counter, made "put all the cups on the table" go back twice in vain).
    """
    picked_none = held or out.result.message.startswith(place.PICK_FAILED)
    if not picked_none or out.result.status is not PlanStatus.NO_VALID_GOAL:
        return True
    p = np.asarray(last.outcome.placement.X_WO.xyz)
    return any(np.linalg.norm(np.asarray(scene.object(o).pose.xyz) - p) <= BLOCK_RADIUS for o in left)


def _need(group) -> int:
    """How many objects of ``group`` to move: its count (all: every candidate) less those already there."""
    return (len(group.objects) if group.count is None else group.count) - len(group.already)


def _hold(scene: Scene, g: Grounding, left: list[str], settings: RunSettings, rng, worlds: Worlds, seed, keep_tree,
          clock) -> Outcome:
    """The last object of "pick up two cans": a pick (:mod:`lazyground.tasks.reach`) over the candidates left, held."""
    sub = Grounding(g.request, "pick", tuple(i for i in g.interpretations if i.action == "pick" and i.objects[0] in left),
                    g.notes)
    out = reach.run(scene, sub, settings, rng, worlds, seed=seed, keep_tree=keep_tree, clock=clock)
    if not out.result.solved:
        return out
    region = out.result.goal_region
    world = worlds.get()
    frame = frame_of(scene.robot)
    X_WG = world.frame_pose(frame, out.result.path[-1])
    grasp = Grasp(region.object, region.id, region.label, frame, X_WG,
                  X_WG.inverse().compose(scene.object(region.object).pose.pose()))
    steps = tuple(replace(s, label=f"pick {region.object} (held)") for s in out.steps)
    return replace(out, steps=steps, held=grasp)


def _records(g: Grounding, done: list[_Done], slots: list[int], failure: PlanResult | None, picking: bool
             ) -> tuple[ObjectStep, ...]:
    """Per group in order: the objects already there, those moved (where, which step), those not done (why)."""
    out: list[ObjectStep] = []
    index = 0  # the pick step of each done object in the combined steps
    first_step = {}
    for d in done:
        first_step[id(d)] = index
        index += len(d.outcome.steps)
    for k, group in enumerate(g.groups):
        out += [ObjectStep(o, "already there", _support(g, o), "not moved") for o in group.already]
        mine = [d for d in done if d.group == k]
        for d in mine:
            others = [o for o in d.among if o != d.object]
            why = f"chosen among {', '.join(d.among)}: the planner reached it first" if others else ""
            if d.outcome.fallbacks:  # place.run's notes say which and why ("picked X but could not place it ...")
                why += f"; {d.outcome.fallbacks} picked before it could not be placed (notes)"
            if d.outcome.held is not None:
                out.append(ObjectStep(d.object, "held", None, why, step=first_step[id(d)]))
            else:
                status = "stowed" if picking else "done"
                out.append(ObjectStep(d.object, status, d.outcome.placement.target, why, d.outcome.placement,
                                      first_step[id(d)]))
        missing = slots.count(k) - len(mine)
        if missing:
            why = failure.message if failure is not None else "not planned"
            why = why if why.startswith(group.phrase) else f"{group.phrase}: {why}"
            moved_ = {d.object for d in mine}
            left = [o for o in group.objects if o not in group.already and o not in moved_]
            # "all": the objects not done are the candidates left; a count names none (any of them would do)
            names = left if group.count is None and len(left) == missing else [None] * missing
            out += [ObjectStep(o, "not done", None, why) for o in names]
    return tuple(out)


def _support(g: Grounding, object_id: str) -> str | None:
    """A target of ``object_id``'s interpretations (where it already rests, for the report)."""
    return next((i.target for i in g.interpretations if i.objects[0] == object_id), None)


def _failed(seed, status: PlanStatus, message: str) -> PlanResult:
    return PlanResult(status, seed, None, None, None, 0, 0, [], 0, 0.0, 0.0, 0.0, message)


def summary(records) -> str:
    """One line: what was done, stowed, held, already there, and how many not (the first reason)."""
    moved_ = [f"{r.object} -> {r.target}" if r.status == "done" else f"{r.object} stowed on {r.target}"
              for r in records if r.status in ("done", "stowed")]
    moved_ += [f"{r.object} held" for r in records if r.status == "held"]
    already = [r.object for r in records if r.status == "already there"]
    missing = [r for r in records if r.status == "not done"]
    return (f"done: {', '.join(moved_) or 'none'}" + (f"; already there: {', '.join(already)}" if already else "")
            + (f"; not done: {len(missing)} ({missing[0].why})" if missing else ""))


def _outcome(done: list[_Done], records, notes: list[str], failure: PlanResult | None, names, start: np.ndarray, seed,
             stop: StopCondition, backtracked: int) -> Outcome:
    outcomes = [d.outcome for d in done]
    missing = any(r.status == "not done" for r in records)
    text = summary(records)
    if backtracked:
        notes = notes + [f"backtracked {backtracked} time(s)"]
    status = PlanStatus.SOLVED if not missing else failure.status if failure.status is not PlanStatus.SOLVED else PlanStatus.NO_VALID_GOAL
    steps = tuple(s for o in outcomes for s in o.steps)
    results = [o.result for o in outcomes]
    if results:
        path = np.vstack([results[0].path] + [r.path[1:] for r in results[1:]])
        last = results[-1]
        combined = place.combine(results, status, path, last.goal, last.goal_region, sum(r.time_s for r in results),
                                 text if missing else "")
    else:
        combined = replace(failure or _failed(seed, status, text), status=status, message=text,
                           time_s=stop.elapsed(), path=None if missing else np.array([start]))  # nothing to move
    last = outcomes[-1] if outcomes else None
    placed = next((o for o in reversed(outcomes) if o.placement is not None), None)
    return Outcome(combined, steps, names, tuple(notes) + (text,), placed.lift if placed else None,
                   placed.placement if placed else None, sum(o.fallbacks for o in outcomes), objects=records,
                   held=last.held if last else None)


def validate_several(outcome: Outcome, scene: Scene, resolution: float) -> list[str]:
    """Re-check every step of a several-object outcome at ``resolution``, replaying the scene: each pick
    in the scene as the earlier steps left it (placed objects are obstacles), each lift and place with the
    object attached, each release where the gripper let go; returns the problems found."""
    from lazyground.planning.rrt import path_is_valid

    problems = []
    scenes = scenes_per_step(outcome, scene)
    for k, (step, current) in enumerate(zip(outcome.steps, scenes)):
        worlds = Worlds(current, visual=False)
        world = worlds.get()
        if step.grasp is None:  # a pick: from where the last step ended, the robot alone
            if not np.allclose(step.result.path[0], world.start, atol=1e-9):
                problems.append(f"{step.label} does not start where the last step ended")
            if path_is_valid(world.space, world, step.result.path, resolution) >= 0:
                problems.append(f"{step.label} collides")
            continue
        carrying = worlds.get(step.grasp)
        if step.lift is not None and not place.lift_is_clear(world, carrying, step.lift.path, resolution):
            problems.append(f"{step.label}: the lift-off collides after leaving the support")
        if path_is_valid(carrying.space, carrying, step.result.path, resolution) >= 0:
            problems.append(f"{step.label} collides (with the carried object)")
        X_WO = carrying.frame_pose(step.grasp.frame, step.result.path[-1]).compose(step.grasp.X_GO)
        if step.placement is None or not np.allclose(X_WO.xyz, step.placement.X_WO.xyz, atol=1e-6):
            problems.append(f"{step.label}: the object is not where the gripper released it")
    return problems
