"""Plan reports as JSON and as a few human-readable lines (the CLI prints these).

The report itself is :class:`lazyground.plan_report.PlanReport`.
"""

from __future__ import annotations

from lazyground.motion.export import motion_line, motion_to_json, trajectory_to_json
from lazyground.motion.steps import report_trajectory
from lazyground.plan_report import PlanReport
from lazyground.planning.problem import proven_unreachable
from lazyground.settings import Algorithm, Kinematics
from lazyground.tolerance import goal_tolerance_json


def _r(x: float, nd: int = 6) -> float:
    return round(float(x), nd)


def report_to_json(report: PlanReport) -> dict:
    """The JSON document of ``lazyground plan --json``."""
    res = report.result
    chosen = report.chosen
    out = {
        "status": res.status.value,
        "message": res.message,
        "request": report.request,
        "scene": report.scene,
        "seed": report.seed,
        "strategy": report.settings.planner.strategy,
        "algorithm": report.settings.planner.algorithm,
        "goal_bias": report.settings.planner.goal_bias,
        "kinematics": report.settings.planner.kinematics,
        "objective": report.settings.planner.objective,
        # objective shortest/fastest: each better solution found, with the seconds since the step began (#30)
        "improvements": [i.to_json() for i in report.outcome.improvements] if report.outcome is not None else [],
        "action": report.grounding.action,
        "ambiguous": report.grounding.ambiguous,
        "interpretations": [i.to_json() for i in report.grounding.interpretations],
        "chosen": {
            "interpretation": chosen.id if chosen else None,
            "goal_region": res.goal_region.id if res.goal_region else None,
            "object": report.chosen_object,
            "goal_sample": res.goal.q.round(9).tolist() if res.goal is not None else None,
            "goal_configuration": res.goal.end.round(9).tolist() if res.goal is not None else None,
        },
        "goal_tolerance": goal_tolerance_json(res.regions),  # IK goals: the error allowed from the region (docs/fetch.md)
        "joint_names": list(report.joint_names),
        "path": res.path.round(9).tolist() if res.path is not None else None,
        "path_length": _r(res.path_length),
        "cusps": report.cusps,  # car kinematics: gear changes along the path (path_length is then the driven length)
        "time_s": _r(report.time_s),
        "time_split_s": {
            "grounding": _r(report.grounding_s),
            "goal_sampling": _r(res.goal_sampling_s),
            "collision_checking": _r(res.collision_s),
            "other": _r(res.other_s),
        },
        "setup_s": _r(report.setup_s),
        # the whole request as the user waits for it (api.plan's wall time less setup_s), split into parts adding up to it
        "total_s": _r(report.total_s) if report.total_s is not None else None,
        "total_split_s": {k: _r(v) for k, v in report.total_split_s.items()} if report.total_s is not None else None,
        "iterations": res.iterations,
        "tree_size": res.tree_size,
        "goal_samples": len(res.goal_samples),
        "resamplings": res.resamplings,
        "samples": [
            {"region": res.regions[s.region].id, "weight": _r(s.weight), "attempts": s.attempts,
             "rewards": s.rewards, "penalties": s.penalties}
            for s in res.goal_samples
        ],
        "regions": {r.id: st.to_json() for r, st in zip(res.regions, res.region_stats)},
        # interpretations the goal source dropped before sampling: all their regions proven unreachable (#33)
        "proven_unreachable": _proven_json(res),
        "notes": list(report.grounding.notes) + list(report.notes),
        # several objects (#30): the groups asked for and, per object, done / already there / not done and why
        "groups": [g.to_json() for g in report.grounding.groups],
        "objects": [o.to_json() for o in report.outcome.objects] if report.outcome is not None else [],
    }
    if report.motion is not None:
        out.update(motion_to_json(report.motion))
    if report.steps:
        out["steps"] = [report_to_json(report.step_report(s)) | _step_json(s) for s in report.steps]
        out.update(_pick_and_place_json(report.outcome))
        joined = report_trajectory(report)  # the steps' trajectories with the gripper events between
        out["trajectory"] = trajectory_to_json(joined) if joined is not None else None
    return out


def _proven_json(res) -> dict | None:
    """``{"interpretations": k, "of": N, "by": "reach prior"}``, or None when no region was proven unreachable."""
    k, n, why = proven_unreachable(res.regions, res.region_stats)
    return {"interpretations": k, "of": n, "by": why} if why else None


def _step_json(step) -> dict:
    """What one step of a task did: its label, the object it carried, where it put it down (several objects, #30)."""
    out = {"label": step.label, "carried": step.attached}
    if step.placement is not None:
        p = step.placement
        out["placement"] = {"region": p.region, "target": p.target, "X_WO": p.X_WO.to_json()}
    return out


def _pick_and_place_json(outcome) -> dict:
    """The keys a pick-and-place document adds (the names of the earlier ``extra`` dict)."""
    out: dict = {"fallbacks": outcome.fallbacks}
    grasp = outcome.grasp
    if grasp is not None:
        out["picked"] = grasp.object_id
        out["grasp"] = {"region": grasp.region, "label": grasp.label, "X_WG": grasp.X_WG.to_json(), "X_GO": grasp.X_GO.to_json()}
    if outcome.placement is not None:
        p = outcome.placement
        out["placement"] = {"region": p.region, "target": p.target, "X_WO": p.X_WO.to_json()}
    if outcome.lift is not None:
        out["lift"] = {"height": outcome.lift.height, "path": outcome.lift.path.round(9).tolist()}
    return out


def report_lines(report: PlanReport) -> list[str]:
    """A short human summary."""
    res = report.result
    g = report.grounding
    lines = [f"request: {report.request!r} on scene {report.scene} (seed {report.seed}, {_planner_label(report.settings.planner)})"]
    kinds = "ambiguous: " if g.ambiguous else ""
    lines.append(f"interpretations ({kinds}{len(g.interpretations)}): " + ", ".join(i.id for i in g.interpretations))
    for note in g.notes + report.notes:
        lines.append(f"note: {note}")
    for o in report.outcome.objects if report.outcome is not None else ():
        lines.append(f"object {o.object or '-'}: {o.status}" + (f" ({o.target})" if o.target else "") + (f": {o.why}" if o.why else ""))
    if res.solved:
        lines.append(
            f"reached: {report.chosen.id} via goal region {res.goal_region.id}"
        )
        driven = "" if report.cusps is None else f" driven, {report.cusps} gear change(s)"
        lines.append(
            f"path: {len(res.path)} waypoints, length {res.path_length:.3f}{driven}; time {report.time_s:.3f} s "
            f"(goal sampling {res.goal_sampling_s:.3f}, collision {res.collision_s:.3f}); "
            f"{res.iterations} iterations, tree {res.tree_size}, {len(res.goal_samples)} goal samples, {res.resamplings} resamplings"
        )
        lines.extend(motion_line(s.motion) for s in (report, *report.steps) if s.motion is not None)
    else:
        lines.append(f"status: {res.status.value}: {res.message}")
        lines.append(f"time {report.time_s:.3f} s; {res.iterations} iterations, tree {res.tree_size}, {len(res.goal_samples)} goal samples")
    if report.total_s is not None:
        split = ", ".join(f"{k} {v:.3f}" for k, v in report.total_split_s.items())
        lines.append(f"request: {report.total_s:.3f} s ({split}); world build {report.setup_s:.3f} s")
    return lines



def _planner_label(settings) -> str:
    if settings.algorithm is Algorithm.BIDIRECTIONAL:  # no goal bias in the two-tree planner
        return f"{settings.strategy}, bidirectional{_car(settings)}"
    return f"{settings.strategy}, bias {settings.goal_bias:g}{_car(settings)}"


def _car(settings) -> str:
    return "" if settings.kinematics is Kinematics.HOLONOMIC else f", {settings.kinematics}"
