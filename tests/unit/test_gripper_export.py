"""Gripper events in every export (issue #30): the CSV's gripper column, GripperCommands beside the ROS file."""

import numpy as np
import yaml

from lazyground.motion.export import gripper_path, read_ros_trajectory, read_trajectory_csv, \
    write_ros_trajectory, write_trajectory
from lazyground.motion.trajectory import Limits, Trajectory


def pick_and_place(events=((1.0, "close gripper"), (3.0, "open gripper"))) -> Trajectory:
    t = np.linspace(0.0, 4.0, 9)
    q = np.column_stack([t, -t])
    zero = np.zeros_like(q)
    return Trajectory(("a", "b"), (False, False), t, q, zero, zero, Limits(np.ones(2), np.ones(2)), "test",
                      events=tuple(events))


def test_csv_has_a_gripper_column_closed_between_the_events(tmp_path):
    write_trajectory(pick_and_place(), tmp_path / "t.csv")
    back = read_trajectory_csv(tmp_path / "t.csv")
    assert back["joint_names"] == ["a", "b"] and back["q"].shape == (9, 2) and back["qdd"].shape == (9, 2)
    # samples at 0, 0.5, ..., 4: closed from 1.0 up to (not including) 3.0
    assert back["gripper"].tolist() == [0, 0, 1, 1, 1, 1, 0, 0, 0]


def test_ros_output_has_gripper_commands_beside_the_joint_trajectory(tmp_path):
    written = write_ros_trajectory(pick_and_place(), tmp_path / "t.yaml", open_position=0.05)
    assert written == [tmp_path / "t.yaml", gripper_path(tmp_path / "t.yaml")]
    assert read_ros_trajectory(tmp_path / "t.yaml")["q"].shape == (9, 2)
    commands = yaml.safe_load(gripper_path(tmp_path / "t.yaml").read_text())
    assert commands == [
        {"time_from_start": {"sec": 1, "nanosec": 0}, "command": {"position": 0.0, "max_effort": 0.0}},
        {"time_from_start": {"sec": 3, "nanosec": 0}, "command": {"position": 0.05, "max_effort": 0.0}},
    ]


def test_a_motion_without_events_writes_no_gripper_file(tmp_path):
    assert write_ros_trajectory(pick_and_place(()), tmp_path / "t.yaml") == [tmp_path / "t.yaml"]
    assert not gripper_path(tmp_path / "t.yaml").exists()
    write_trajectory(pick_and_place(()), tmp_path / "t.csv")
    assert not read_trajectory_csv(tmp_path / "t.csv")["gripper"].any()
