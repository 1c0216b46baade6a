"""Several timed steps as one motion: pick and place, with the gripper events between them."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lazyground.motion.trajectory import Trajectory

GRIPPER_DWELL_S = 0.5  # the robot rests this long while the gripper closes or opens


def join(trajectories: list[Trajectory], events: list[str | None], dwell: float = GRIPPER_DWELL_S) -> Trajectory:
    """The trajectories one after another; after trajectory k, if ``events[k]`` names one, the robot
    rests ``dwell`` s for it (recorded in ``events`` at the rest's start).

    Wrapping coordinates continue from where the previous trajectory ended (whole turns added).
    """
    first = trajectories[0]
    dt = float(first.t[1] - first.t[0]) if len(first.t) > 1 else dwell
    wrap = np.array(first.wrap, bool)
    t, q, qd, qdd = [first.t[:1]], [first.q[:1]], [first.qd[:1]], [first.qdd[:1]]
    out_events = []
    for k, tr in enumerate(trajectories):
        end_t, end_q = t[-1][-1], q[-1][-1]
        shift = np.where(wrap, np.round((end_q - tr.q[0]) / (2 * np.pi)) * 2 * np.pi, 0.0)
        t.append(tr.t[1:] + end_t)
        q.append(tr.q[1:] + shift)
        qd.append(tr.qd[1:])
        qdd.append(tr.qdd[1:])
        out_events.extend((e_t + end_t, e) for e_t, e in tr.events)
        what = events[k] if k < len(events) else None
        if what:
            end_t, end_q = t[-1][-1] if len(t[-1]) else end_t, q[-1][-1] if len(q[-1]) else end_q
            out_events.append((float(end_t), what))
            rest = end_t + np.arange(1, int(np.ceil(dwell / dt - 1e-9)) + 1) * dt
            t.append(rest)
            q.append(np.tile(end_q, (len(rest), 1)))
            qd.append(np.zeros((len(rest), len(end_q))))
            qdd.append(np.zeros((len(rest), len(end_q))))
    return replace(first, t=np.concatenate(t), q=np.vstack(q), qd=np.vstack(qd), qdd=np.vstack(qdd),
                   curve=" | ".join(tr.curve for tr in trajectories), time_s=sum(tr.time_s for tr in trajectories),
                   events=tuple(out_events))


def report_trajectory(report) -> Trajectory | None:
    """A plan report's whole timed motion: its own, or its steps' joined with their gripper events."""
    if report.motion is not None and report.motion.trajectory is not None:
        return report.motion.trajectory
    steps = [s.motion.trajectory for s in report.steps if s.motion is not None and s.motion.trajectory is not None]
    if not steps or len(steps) != len(report.steps):
        return None
    # a step that ends at a grasp closes the gripper, one that carries an object opens it where it puts it down
    # (several objects, #30: close, open, close, open ...; picking up several ends closed on the held object)
    return join(steps, ["open gripper" if s.grasp is not None else "close gripper" for s in report.steps])


def pick_and_place_motions(world, carrying, pick, lift_path: np.ndarray, place, settings, rng):
    """Shorten and time both steps of a pick and place.

    The pick is shortened and timed in ``world``; the place step in ``carrying`` (the object
    in the gripper), preceded by the lift-off timed waypoint to waypoint (it may graze the
    support the object leaves, so it is not reshaped).

    Returns:
        (pick result, pick Motion, place result, place Motion); the place Motion's trajectory
        includes the lift. Both results carry the shortened paths.
    """
    from lazyground.motion.pipeline import motion_for_world, timing_settings
    from lazyground.motion.trajectory import time_path

    pick, pick_motion = motion_for_world(world, pick, settings, rng)
    place, place_motion = motion_for_world(carrying, place, settings, rng)
    if place_motion is not None and place_motion.trajectory is not None:
        planner = settings.planner
        lift = time_path(world.space, world, lift_path, place_motion.trajectory.limits, planner.resolution / planner.validation_factor,
                         replace(timing_settings(settings.motion), speed=1.0, blends=()))
        # the limits are already scaled by speed: time the lift under the same ones
        place_motion = replace(place_motion, trajectory=join([lift, place_motion.trajectory], []),
                               timing_s=place_motion.timing_s + lift.time_s)
    return pick, pick_motion, place, place_motion
