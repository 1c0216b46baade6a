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
"""

from __future__ import annotations

GROWN, RETIRED = -1, -2  # ``fails`` of a sample whose tree took a free step / whose sample was retired


class BlockedTrees:
    """Per goal sample: blocked steps from its root while the tree is only its root, and the live count."""

    def __init__(self, after: int, on_change=None):
        """Args: the collided steps that make a root-only tree blocked; ``on_change(gi, blocked)``, called when
        sample ``gi``'s tree becomes blocked (True) or grows after being blocked (False), or None."""
        self.after, self.on_change = after, on_change
        self.fails: list[int] = []  # per sample: collided steps from its root so far, or GROWN / RETIRED
        self.live = 0  # samples neither blocked nor retired

    def add(self) -> None:
        """A new goal sample (its tree is its root)."""
        self.fails.append(0)
        self.live += 1

    def blocked(self, gi: int) -> bool:
        return self.fails[gi] >= self.after

    def step(self, gi: int, free: bool) -> None:
        """A step from sample ``gi``'s tree was made (``free``: it added a node)."""
        f = self.fails[gi]
        if f < 0:
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

    def retire(self, gi: int) -> None:
        """Sample ``gi`` will never be selected again (its approach failed the fine re-check)."""
        if self.fails[gi] != RETIRED and not self.blocked(gi):
            self.live -= 1
        self.fails[gi] = RETIRED
