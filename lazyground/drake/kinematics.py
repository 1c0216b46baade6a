"""Forward kinematics: the one place that asks the plant where a frame is.

Used by the world's ``frame_pose``, by IK to judge its answers, by the reach
map and by the Meshcat view.
"""

from __future__ import annotations

import numpy as np
from pydrake.math import RigidTransform

from lazyground.geometry import Pose


class Kinematics:
    """World poses of a plant's frames at full position vectors.

    Args:
        plant: a finalized MultibodyPlant (kept, not copied).
        robot: the robot's ModelInstanceIndex; frame names are looked up there first.
    """

    def __init__(self, plant, robot):
        self.plant = plant
        self.robot = robot
        self._context = plant.CreateDefaultContext()
        self._frames: dict[str, object] = {}  # per instance, bounded by the plant's frames

    def frame(self, name: str):
        """The robot's frame called ``name`` (else any model instance's).

        Raises:
            RuntimeError: no frame of that name in the plant (Drake's error).
        """
        if name not in self._frames:
            has = self.plant.HasFrameNamed(name, self.robot)
            self._frames[name] = self.plant.GetFrameByName(name, self.robot) if has else self.plant.GetFrameByName(name)
        return self._frames[name]

    def X_WF(self, frame, q_full: np.ndarray) -> RigidTransform:
        """World pose of ``frame`` (a name or a Drake frame) at full plant positions ``q_full``."""
        if isinstance(frame, str):
            frame = self.frame(frame)
        self.plant.SetPositions(self._context, q_full)
        return self.plant.CalcRelativeTransform(self._context, self.plant.world_frame(), frame)

    def matrix(self, frame, q_full: np.ndarray) -> np.ndarray:
        """World pose of ``frame`` at ``q_full`` as a 4x4 matrix."""
        return self.X_WF(frame, q_full).GetAsMatrix4()

    def pose(self, frame, q_full: np.ndarray) -> Pose:
        """World pose of ``frame`` at ``q_full`` as a :class:`Pose`."""
        return Pose.from_matrix(self.matrix(frame, q_full))
