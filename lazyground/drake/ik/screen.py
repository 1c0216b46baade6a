"""The target screen: why an IK target pose fails before any solve (#19).

Two cheap tests, in order: the wrist point lies far outside the sampled reach
(:mod:`lazyground.drake.ik.reach`), or the hand alone collides there, whatever the arm
(:mod:`lazyground.drake.ik.hand_probe`). Each is switched by :class:`IKSettings`.
"""

from __future__ import annotations

import numpy as np

from lazyground.drake.arm_reach import end_effector_frame
from lazyground.drake.ik.hand_probe import hand_probe
from lazyground.drake.ik.reach import reach_map
from lazyground.drake.ik.settings import DEFAULT_IK_SETTINGS, IKSettings
from lazyground.tolerance import accepted_error


class TargetScreen:
    """Screens target poses of the robot frames ``frames`` in ``world``.

    Args:
        world: the DrakeWorld.
        frames: the robot frames targets will be given for.
        settings: ``reach_check``, ``reach_margin``, ``hand_check`` and the tolerances (the probe's slack).
    """

    def __init__(self, world, frames, settings: IKSettings):
        self.world = world
        self.settings = settings
        accepted = accepted_error(settings.position_tolerance, settings.orientation_tolerance)
        self._probes = {f: hand_probe(world, f, *accepted) for f in dict.fromkeys(frames)} if settings.hand_check else {}

    def reasons(self, frame: str, X_WT: np.ndarray) -> list[str]:
        """Why each target pose (B, 4, 4) of ``frame`` fails before any solve ("" for none): its wrist point is
        out of reach, or the hand alone collides there (every answer would)."""
        s = self.settings
        reasons = [""] * len(X_WT)
        if s.reach_check:
            near = reach_map(self.world, frame).plausible_all(X_WT, s.reach_margin)
            reasons = ["" if ok else "out of reach" for ok in near]
        rest = [i for i, r in enumerate(reasons) if not r]  # the probe costs ~30 us a target: only where reach did not decide
        if frame in self._probes and rest:
            for i in np.asarray(rest)[self._probes[frame].blocked(X_WT[rest])]:
                reasons[i] = "hand in collision"
        return reasons


def warm_screen(world, settings: IKSettings = DEFAULT_IK_SETTINGS) -> None:
    """Build the hand probe of ``world``'s end-effector frame now (set-up: once per world, cached as
    :func:`hand_probe` caches it; a request's goal source then finds it built), when its robot has one and
    ``settings.hand_check`` is on. A run's IK settings take their tolerances from the defaults."""
    frame = end_effector_frame(world)
    if settings.hand_check and frame is not None:
        hand_probe(world, frame, *accepted_error(settings.position_tolerance, settings.orientation_tolerance))
