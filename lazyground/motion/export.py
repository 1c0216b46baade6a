"""Trajectories out to files a controller or another tool can read, and back.

- JSON: ``{"joint_names", "wrap", "trajectory": {"t", "q", "qd", "qdd"}, ...}``; ``wrap`` names
  the coordinates that are angles without limits (continuous joints, a car's heading):
  their ``q`` is unwrapped (continuous along the motion), so interpolate it linearly.
- CSV: one row per sample, ``t, q.<joint>..., qd.<joint>..., qdd.<joint>..., gripper``; ``gripper`` is
  1 while the gripper is closed, 0 while open (it changes at the sample where the event's rest begins).
- ROS: a ``trajectory_msgs/msg/JointTrajectory`` as YAML (``header``, ``joint_names``,
  ``points`` with ``positions``, ``velocities``, ``accelerations``, ``effort`` and
  ``time_from_start: {sec, nanosec}``), e.g. for ``ros2 topic pub`` or a
  FollowJointTrajectory goal; beside it, when the motion has gripper events, ``<name>.gripper.yaml``:
  a list of ``{time_from_start, command}`` with ``command`` a ``control_msgs/msg/GripperCommand``
  (``position`` in metres, ``max_effort``) sent at that time (issue #30).
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import yaml

from lazyground.motion import TRAJECTORY_FORMATS as FORMATS
from lazyground.motion.trajectory import Trajectory

CLOSE, OPEN = "close gripper", "open gripper"  # the events lazyground.motion.steps records


def gripper_state(traj: Trajectory) -> np.ndarray:
    """Per sample of ``traj``: 1.0 while the gripper is closed, 0.0 while open (open at the start)."""
    state = np.zeros(len(traj.t))
    for t, event in sorted(traj.events):
        if event in (CLOSE, OPEN):
            state[traj.t >= t - 1e-12] = 1.0 if event == CLOSE else 0.0
    return state


def _stamp(t: float) -> dict:
    ns = int(round(float(t) * 1e9))
    return {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000}


def ros_gripper_commands(traj: Trajectory, open_position: float = 0.04, closed_position: float = 0.0,
                         max_effort: float = 0.0) -> list[dict]:
    """The gripper events as timed ``control_msgs/msg/GripperCommand`` messages (plain data).

    Args:
        traj: the trajectory whose ``events`` say when the gripper closes and opens.
        open_position: the command's ``position`` (metres between the fingers) to open.
        closed_position: its ``position`` to close (the controller stops at the object).
        max_effort: the command's ``max_effort`` (0: the controller's default).
    """
    return [{"time_from_start": _stamp(t),
             "command": {"position": float(closed_position if e == CLOSE else open_position),
                         "max_effort": float(max_effort)}}
            for t, e in sorted(traj.events) if e in (CLOSE, OPEN)]




def trajectory_to_json(traj: Trajectory) -> dict:
    """The ``trajectory`` document of ``--json`` and of ``--trajectory FILE.json``."""
    qd_ratio, qdd_ratio = traj.peak_ratios
    return {
        "joint_names": list(traj.joint_names),
        "wrap": [n for n, w in zip(traj.joint_names, traj.wrap) if w],
        "duration_s": round(traj.duration, 9),
        "sample_rate_hz": round(1.0 / (traj.t[1] - traj.t[0]), 9) if len(traj.t) > 2 else None,
        "limits_bind": traj.limits_bind,
        "peak_velocity_ratio": round(qd_ratio, 6),
        "peak_acceleration_ratio": round(qdd_ratio, 6),
        "velocity_limits": traj.limits.velocity.round(9).tolist(),
        "acceleration_limits": traj.limits.acceleration.round(9).tolist(),
        "curve": traj.curve,
        "events": [{"t": round(t, 9), "event": e} for t, e in traj.events],
        "trajectory": {
            "t": traj.t.round(9).tolist(),
            "q": traj.q.round(9).tolist(),
            "qd": traj.qd.round(9).tolist(),
            "qdd": traj.qdd.round(9).tolist(),
        },
    }


def write_trajectory(traj: Trajectory, path: str | Path) -> None:
    """Write ``traj`` as CSV or JSON, by the file's suffix.

    Raises:
        ValueError: the suffix is neither .csv nor .json.
        OSError: the file cannot be written.
    """
    path = Path(path)
    if path.suffix.lower() == ".json":
        path.write_text(json.dumps(trajectory_to_json(traj), indent=1) + "\n")
    elif path.suffix.lower() == ".csv":
        with path.open("w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["t"] + [f"{k}.{n}" for k in ("q", "qd", "qdd") for n in traj.joint_names] + ["gripper"])
            for row in np.column_stack([traj.t, traj.q, traj.qd, traj.qdd, gripper_state(traj)]):
                out.writerow([repr(float(x)) for x in row])
    else:
        raise ValueError(f"{path}: trajectory files end in {' or '.join(FORMATS)}")


def read_trajectory_csv(path: str | Path) -> dict[str, np.ndarray]:
    """A CSV written by :func:`write_trajectory`: ``{"t", "q", "qd", "qdd", "gripper", "joint_names"}``
    (``gripper`` all zeros for a file without the column)."""
    with Path(path).open(newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], float).reshape(-1, len(rows[0]))
    gripper = data[:, -1] if header[-1] == "gripper" else np.zeros(len(data))
    n = (len(header) - 1 - (header[-1] == "gripper")) // 3
    names = [h.split(".", 1)[1] for h in header[1 : n + 1]]
    return {"joint_names": names, "t": data[:, 0], "q": data[:, 1 : n + 1], "qd": data[:, n + 1 : 2 * n + 1],
            "qdd": data[:, 2 * n + 1 : 3 * n + 1], "gripper": gripper}


def ros_joint_trajectory(traj: Trajectory, frame_id: str = "") -> dict:
    """``trajectory_msgs/msg/JointTrajectory`` as plain data (ROS 2 field names)."""
    points = []
    for t, q, qd, qdd in zip(traj.t, traj.q, traj.qd, traj.qdd):
        points.append({
            "positions": [float(x) for x in q],
            "velocities": [float(x) for x in qd],
            "accelerations": [float(x) for x in qdd],
            "effort": [],
            "time_from_start": _stamp(t),
        })
    return {"header": {"stamp": {"sec": 0, "nanosec": 0}, "frame_id": frame_id}, "joint_names": list(traj.joint_names), "points": points}


def gripper_path(path: str | Path) -> Path:
    """Where :func:`write_ros_trajectory` puts the gripper commands beside ``path``: ``<stem>.gripper.yaml``."""
    path = Path(path)
    return path.with_name(path.stem + ".gripper.yaml")


def write_ros_trajectory(traj: Trajectory, path: str | Path, **gripper) -> list[Path]:
    """Write ``traj`` as a ``trajectory_msgs/JointTrajectory`` YAML file and, when it has gripper events,
    their ``control_msgs/GripperCommand`` sequence beside it (:func:`gripper_path`).

    Args:
        traj: the trajectory.
        path: the JointTrajectory file.
        **gripper: :func:`ros_gripper_commands`' positions and effort.

    Returns:
        The files written.

    Raises:
        OSError: a file cannot be written.
    """
    dump = dict(sort_keys=False, default_flow_style=None, width=1 << 16)
    Path(path).write_text(yaml.safe_dump(ros_joint_trajectory(traj), **dump))
    commands = ros_gripper_commands(traj, **gripper)
    if not commands:
        return [Path(path)]
    gripper_path(path).write_text(yaml.safe_dump(commands, **dump))
    return [Path(path), gripper_path(path)]


def read_ros_trajectory(path: str | Path) -> dict[str, np.ndarray]:
    """A JointTrajectory YAML back as ``{"joint_names", "t", "q", "qd", "qdd"}``.

    Raises:
        ValueError: the file is not a JointTrajectory (missing keys, ragged points).
    """
    doc = yaml.safe_load(Path(path).read_text())
    try:
        names = list(doc["joint_names"])
        pts = doc["points"]
        t = np.array([p["time_from_start"]["sec"] + p["time_from_start"]["nanosec"] * 1e-9 for p in pts], float)
        q, qd, qdd = (np.array([p[k] for p in pts], float).reshape(len(pts), len(names)) for k in ("positions", "velocities", "accelerations"))
    except (KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"{path}: not a trajectory_msgs/JointTrajectory: {exc}") from None
    return {"joint_names": names, "t": t, "q": q, "qd": qd, "qdd": qdd}


def motion_to_json(motion) -> dict:
    """The keys a plan report's JSON gains from its :class:`~lazyground.motion.pipeline.Motion`."""
    sc = motion.shortcut
    out = {
        "raw_path": sc.raw_path.round(9).tolist(),
        "raw_path_length": round(sc.raw_length, 6),
        "shortcut": {"status": sc.status.value, "iterations": sc.iterations, "accepted": sc.accepted,
                     "time_s": round(motion.shortcut_s, 6)},
        "timing_s": round(motion.timing_s, 6),
        "trajectory": trajectory_to_json(motion.trajectory) if motion.trajectory is not None else None,
    }
    return out


def motion_line(motion) -> str:
    """One human line: lengths, duration, cost."""
    sc, tr = motion.shortcut, motion.trajectory
    line = f"motion: path length {sc.raw_length:.3f} -> {sc.length:.3f} ({sc.status.value}, {len(sc.raw_path)} -> {len(sc.path)} waypoints)"
    if tr is not None:
        line += f"; trajectory {tr.duration:.2f} s ({tr.curve}{', limits bind' if tr.limits_bind else ''})"
    return line + f"; shortcut {motion.shortcut_s:.3f} s, timing {motion.timing_s:.3f} s"


def write_outputs(report, trajectory: str | None = None, ros_trajectory: str | None = None) -> list[str]:
    """Write the trajectory files asked for, for a solved report (pick and place: the steps joined).

    Args:
        report: the PlanReport.
        trajectory: a ``.csv`` or ``.json`` file, or None.
        ros_trajectory: a ``trajectory_msgs/JointTrajectory`` YAML file, or None.
    Returns:
        One line per file written, or the note why none was (for the CLI to print).
    """
    if not (trajectory or ros_trajectory):
        return []
    from lazyground.motion.steps import report_trajectory

    traj = report_trajectory(report)
    if traj is None:
        motion = report.motion
        return ["note: no trajectory to write" + (f" ({motion.note})" if motion is not None and motion.note else "")]
    lines = []
    if trajectory:
        write_trajectory(traj, trajectory)
        lines.append(f"wrote {trajectory}")
    if ros_trajectory:
        lines.extend(f"wrote {p}" for p in write_ros_trajectory(traj, ros_trajectory))
    return lines
