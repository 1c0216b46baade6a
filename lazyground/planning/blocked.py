"""Goal trees that cannot grow out of their root (issue #33): measured by the search, per goal sample.

On an arm rack a can behind a pane whose window admits the hand lengthwise has valid grasp configurations that no
path reaches: its goal tree is its root, and every step from it collides (Panda N = 64, 10 layouts: 58,040 steps
from window cans' roots, none free; the reachable can's trees: 387 free of 10,998). Such a root still drew the
forest's nearest-node queries (a step and a greedy connection from it, each blocked), and while only such trees
exist the search has nothing to grow towards but the start tree, so the goal sampler's budget need not wait for it.

A sample's tree is *blocked* once ``after`` steps from its root have collided and none has been free: its root is
then muted (left out of the whole forest's queries; the strategy may still select it, and a tree that grows after
all is live again, its new nodes queried as any). ``live`` counts the samples not blocked and not retired, kept as
steps are made (O(1) a step, no scan over the samples).
"""

from __future__ import annotations

GROWN, RETIRED = -1, -2  # ``fails`` of a sample whose tree took a free step / whose sample was retired


class BlockedTrees:
    """Per goal sample: blocked steps from its root while the tree is only its root, and the live count."""

    def __init__(self, after: int):
        self.after = after
        self.fails: list[int] = []  # per sample: collided steps from its root so far, or GROWN / RETIRED
        self.roots: list[int] = []  # per sample: its root's node in the goal forest
        self.live = 0  # samples neither blocked nor retired

    def add(self, root: int) -> None:
        """A new goal sample, its tree rooted at forest node ``root``."""
        self.fails.append(0)
        self.roots.append(root)
        self.live += 1

    def blocked(self, gi: int) -> bool:
        return self.fails[gi] >= self.after

    def step(self, tree, gi: int, free: bool) -> None:
        """A step from sample ``gi``'s tree was made (``free``: it added a node); mutes the root in ``tree`` when the
        tree becomes blocked."""
        f = self.fails[gi]
        if f < 0:
            return
        if free:
            self.live += f >= self.after  # blocked, then grew after all
            self.fails[gi] = GROWN
            return
        self.fails[gi] = f + 1
        if f + 1 == self.after:
            self.live -= 1
            tree.mute(self.roots[gi])

    def retire(self, gi: int) -> None:
        """Sample ``gi`` will never be selected again (its approach failed the fine re-check)."""
        if self.fails[gi] != RETIRED and not self.blocked(gi):
            self.live -= 1
        self.fails[gi] = RETIRED
