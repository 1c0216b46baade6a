"""A 2-D toy world with a fake collision checker, for planner tests without Drake."""

from __future__ import annotations

import time

import numpy as np

from lazyground.goals import ConfigGoalSource
from lazyground.planning.space import ConfigSpace
from lazyground.regions import ConfigRegion


class BoxWorld:
    """Axis-aligned rectangular obstacles in [0, 10]^2; a point robot."""

    def __init__(self, boxes):
        self.boxes = np.array(boxes, float).reshape(-1, 4)  # xmin, ymin, xmax, ymax
        self._time = 0.0
        self.checks = 0

    @property
    def check_time(self) -> float:
        return self._time

    def configs_free(self, qs):
        t0 = time.perf_counter()
        qs = np.atleast_2d(qs)
        self.checks += len(qs)
        inside = np.zeros(len(qs), bool)
        for x0, y0, x1, y1 in self.boxes:
            inside |= (qs[:, 0] >= x0) & (qs[:, 0] <= x1) & (qs[:, 1] >= y0) & (qs[:, 1] <= y1)
        self._time += time.perf_counter() - t0
        return ~inside

    def config_free(self, q) -> bool:
        return bool(self.configs_free(q)[0])

    def edge_free(self, a, b, resolution) -> bool:
        return bool(np.all(self.configs_free(SPACE.discretize(a, b, resolution, skip_first=True))))

    def edge_fraction(self, a, b, resolution) -> float:
        qs = SPACE.discretize(a, b, resolution)
        free = self.configs_free(qs)
        if free.all():
            return 1.0
        first_bad = int(np.argmin(free))
        return max(0, first_bad - 1) / (len(qs) - 1)

    def explain(self, q) -> str:
        q = np.asarray(q, float)
        hits = [i for i, (x0, y0, x1, y1) in enumerate(self.boxes) if x0 <= q[0] <= x1 and y0 <= q[1] <= y1]
        return ", ".join(f"robot collides with box {i}" for i in hits) or "no colliding pair found"


class CountingWorld(BoxWorld):
    """A BoxWorld that counts the configurations it is asked about in batches."""

    def __init__(self, boxes):
        super().__init__(boxes)
        self.asked = 0

    def configs_free(self, qs):
        self.asked += len(np.atleast_2d(qs))
        return super().configs_free(qs)


SPACE = ConfigSpace(("x", "y"), np.zeros(2), np.full(2, 10.0))

# A wall at x in [4, 5] with a gap at y in [8, 9]; a box around (8, 2) encloses a pocket.
WALLS = [
    (4, 0, 5, 8),
    (4, 9, 5, 10),
    (6.5, 0.5, 9.5, 0.8),  # pocket: bottom
    (6.5, 3.2, 9.5, 3.5),  # pocket: top
    (6.5, 0.5, 6.8, 3.5),  # pocket: left
    (9.2, 0.5, 9.5, 3.5),  # pocket: right
    (7.0, 6.0, 9.0, 7.5),  # a solid block (goal inside it is invalid)
]
START = np.array([1.0, 1.0])

# Outcomes are bounded by iteration counts, never by the clock (a loaded CI machine must
# give the same answers): a time limit that is never reached, and two iteration budgets.
NO_CLOCK = 1e6  # s
SOLVE_BUDGET = 20_000  # iterations: far more than any seeded solve below needs (a few hundred)
TIMEOUT_BUDGET = 3_000  # iterations: twice what the first resampling in the pocket needs (1,200-1,500)


def region(name, x, y, half=0.3):
    return ConfigRegion(id=name, interpretation=f"go:{name}", object=name,
                        lower=(x - half, y - half), upper=(x + half, y + half))


REACHABLE = region("open", 8.0, 9.0)
UNREACHABLE = region("pocket", 8.0, 2.0)  # valid samples, enclosed
INVALID = region("block", 8.0, 6.75, half=0.5)  # entirely inside the block


def goal_source(world, regions):
    return ConfigGoalSource(tuple(regions), SPACE, world)
