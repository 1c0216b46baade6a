"""Goal trees that cannot grow out of their root (issue #33): measured by the search, per goal sample.

On an arm rack a can behind a pane whose window admits the hand lengthwise has valid grasp configurations that no
path reaches: its goal tree is its root, and every step from it collides (Panda N = 64, 10 layouts: 58,040 steps
from window cans' roots, none free; the reachable can's trees: 387 free of 10,998). While only such trees exist the
search has nothing to grow towards but the start tree, so goal sampling need not wait for it (Cover.ik_allowance),
and the sample's region counts it as a miss (the goal-region chooser's ``block_sample``).

A sample's tree is *blocked* once ``after`` steps from its root have collided and none has been free; a tree that
grows after all is live again. ``live`` counts the samples not blocked and not retired, kept as steps are made (O(1)
a step, no scan over the samples). Blocked roots stay in the forest's queries: muting them (as a car's shut-in
roots are) sometimes muted the reachable can's only sample, whose first steps collide too (Panda N = 64 layout 6:
15,421 IK attempts instead of 180-280), and the forest's greedy connections are what joins that tree.

A sample *ages* once ``age_after`` steps have been made from its tree (the forest's, the strategy's and the greedy
connections') without the search ending: a tree that grows but does not meet the start tree (Fetch rack N = 64
layout 0: the reachable can's first grasp's tree, 24 nodes, 9,131 steps over 20,564 iterations) stops counting as
live, and its region hears of it (the chooser's ``age_sample``) and may get another sample (another grasp). An aged
sample stays in the forest and is still selected: only the goal sampling around it changes.
"""

from __future__ import annotations

GROWN, RETIRED, AGED = -1, -2, -3  # ``fails`` of a sample whose tree took a free step / was retired / aged


class BlockedTrees:
    """Per goal sample: blocked steps from its root while the tree is only its root, and the live count."""

    def __init__(self, after: int, on_change=None, age_after: int = 0, on_age=None):
        """Args: the collided steps that make a root-only tree blocked; ``on_change(gi, blocked)``, called when
        sample ``gi``'s tree becomes blocked (True) or grows after being blocked (False), or None; the steps from a
        tree after which its sample ages (0: never); ``on_age(gi)``, called when a live sample ages, or None."""
        self.after, self.on_change, self.age_after, self.on_age = after, on_change, age_after, on_age
        self.fails: list[int] = []  # per sample: collided steps from its root so far, or GROWN / RETIRED / AGED
        self.steps: list[int] = []  # per sample: steps from its tree so far
        self.live = 0  # samples neither blocked nor retired nor aged

    def add(self) -> None:
        """A new goal sample (its tree is its root)."""
        self.fails.append(0)
        self.steps.append(0)
        self.live += 1

    def blocked(self, gi: int) -> bool:
        return self.fails[gi] >= self.after

    def aged(self, gi: int) -> bool:
        return self.fails[gi] == AGED

    def is_live(self, gi: int) -> bool:
        f = self.fails[gi]
        return f == GROWN or 0 <= f < self.after

    def step(self, gi: int, free: bool) -> None:
        """A step from sample ``gi``'s tree was made (``free``: it added a node)."""
        f = self.fails[gi]
        if f in (RETIRED, AGED):
            return
        if self.age_after:
            self.steps[gi] += 1
            if self.steps[gi] >= self.age_after:
                self._age(gi)
                return
        if f == GROWN:
            return
        if free:
            self.fails[gi] = GROWN
            if f >= self.after:  # blocked, then grew after all
                self.live += 1
                if self.on_change is not None:
                    self.on_change(gi, False)
            return
        self.fails[gi] = f + 1
        if f + 1 == self.after:
            self.live -= 1
            if self.on_change is not None:
                self.on_change(gi, True)

    def _age(self, gi: int) -> None:
        """Sample ``gi``'s tree has had ``age_after`` steps: no longer live (a blocked one was told already)."""
        if self.is_live(gi):
            self.live -= 1
            if self.on_age is not None:
                self.on_age(gi)
        self.fails[gi] = AGED

    def retire(self, gi: int) -> None:
        """Sample ``gi`` will never be selected again (its approach failed the fine re-check)."""
        if self.is_live(gi):
            self.live -= 1
        self.fails[gi] = RETIRED
