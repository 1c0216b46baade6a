"""Worlds for one scene: the caller's prebuilt world, or built on demand, and the time it took.

Every task gets its worlds from here, so a world passed to ``api.plan(..., world=)`` is
used by every task (place included), and set-up time is counted the same way for all.
"""

from __future__ import annotations

from lazyground.planning.stop import default_clock


class Worlds:
    """Builds or returns the DrakeWorld of one scene, optionally carrying an object.

    Worlds carrying an object are cached by (object, frame, grasp pose) for the life of
    this factory (one request), so a fallback that grasps the same object the same way
    does not rebuild it.
    """

    def __init__(self, scene, world=None, visual: bool = True):
        """Args:
            scene: the Scene.
            world: a prebuilt DrakeWorld of ``scene`` without an attachment (optional).
            visual: build worlds with visual geometry (viewers need it).
        """
        self.scene = scene
        self.visual = visual
        self._cache: dict[tuple, object] = {} if world is None else {(): world}
        self.setup_s = 0.0  # seconds spent building worlds so far

    def get(self, grasp=None):
        """The world without an attachment, or carrying ``grasp.object_id`` at ``grasp.X_GO``.

        Args:
            grasp: a :class:`~lazyground.tasks.outcome.Grasp`, or None.
        """
        key = () if grasp is None else (grasp.object_id, grasp.frame, grasp.X_GO.xyz, grasp.X_GO.rpy)
        world = self._cache.get(key)
        if world is None:
            from lazyground.drake.world import Attachment, DrakeWorld

            t0 = default_clock()
            attached = None if grasp is None else Attachment(self.scene.object(grasp.object_id), grasp.frame, grasp.X_GO)
            world = DrakeWorld(self.scene, attached=attached, visual=self.visual)
            self.setup_s += default_clock() - t0
            self._cache[key] = world
        return world

    def warm_kernels(self, kinematics) -> None:
        """Load a Reeds-Shepp car's compiled curves (compile them, the first time on a machine) now, once per
        process, timed as set-up like the world build: not as the request's time (issue #31, first call)."""
        from lazyground.settings import Kinematics

        if Kinematics(kinematics) is Kinematics.REEDS_SHEPP:
            from lazyground.drake import compiled

            t0 = default_clock()
            compiled.warm_up_car()
            self.setup_s += default_clock() - t0

    def warm_goal_caches(self, world, reach_prior: bool) -> None:
        """Build ``world``'s per-world goal-sampling caches now, timed as set-up like the world build (issue #33: they
        depend on the world only, not on the request): the hand probe of the IK target screen
        (:func:`lazyground.drake.ik.screen.warm_screen`, ~0.03 s on a 64-can rack), the IK chain problems of the end
        effector (:func:`lazyground.drake.ik.solvers.warm_problems`, ~0.005 s) and, with ``reach_prior`` on, the
        reach prior (an arm's grids: ~0.5 s there) and an arm's hand for the approach-clearance test
        (:func:`lazyground.drake.approach.warm_hand`, ~0.02 s)."""
        if not hasattr(world, "reach_prior"):  # (a DrakeWorld: test doubles have none of these)
            return
        from lazyground.drake.approach import warm_hand
        from lazyground.drake.ik.screen import warm_screen
        from lazyground.drake.ik.solvers import warm_problems

        t0 = default_clock()
        warm_screen(world)
        warm_problems(world)
        if reach_prior:
            world.reach_prior()
            warm_hand(world)
        self.setup_s += default_clock() - t0
