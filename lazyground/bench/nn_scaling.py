"""Micro-benchmark: does time per iteration stay flat as the tree grows to 100,000 nodes?

Two measurements in one process (compare ratios, not absolute times):

* ``NearestNeighbors`` alone: mean time of one ``add`` + one ``nearest`` in a
  window of iterations just after the index holds ``n`` points;
* the RRT loop of :func:`lazyground.planning.solve` on a toy 8-D unit box with
  a cheap vectorised checker (one ball obstacle) and goal bias 0, so every
  iteration adds a node: the checker is called once per iteration and records
  a timestamp, which gives time per iteration at each tree size.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from lazyground.goals import ConfigGoalSource
from lazyground.planning import ConfigSpace, PlannerSettings, solve
from lazyground.planning.nn import NearestNeighbors
from lazyground.regions import ConfigRegion

DIM = 8
WINDOW = 1000


@dataclass(frozen=True)
class Scaling:
    sizes: tuple[int, ...]
    nn_us: tuple[float, ...]  # microseconds per add + nearest near each size
    rrt_us: tuple[float, ...]  # microseconds per RRT iteration near each size

    def ratio(self, which: str) -> float:
        v = getattr(self, which)
        return v[-1] / v[0]


class _ToyChecker:
    """Free except a ball in the middle; timestamps every edge check (= every iteration)."""

    def __init__(self):
        self.stamps: list[float] = []
        self.check_time = 0.0

    def config_free(self, q) -> bool:
        return bool(np.linalg.norm(np.asarray(q) - 0.5) > 0.2)

    def configs_free(self, qs):
        self.stamps.append(time.perf_counter())
        return np.linalg.norm(np.atleast_2d(qs) - 0.5, axis=1) > 0.2

    def edge_free(self, a, b, resolution) -> bool:
        a, b = np.asarray(a, float), np.asarray(b, float)
        n = max(1, int(np.ceil(np.linalg.norm(b - a) / resolution)))
        return bool(np.all(self.configs_free(a + np.outer(np.arange(1, n + 1) / n, b - a))))

    def explain(self, q) -> str:
        return "inside the ball"


def _windows(stamps: np.ndarray, sizes) -> list[float]:
    return [float(np.mean(np.diff(stamps[n - 1 : n + WINDOW]))) * 1e6 for n in sizes]


def measure(sizes=(1_000, 10_000, 100_000), seed: int = 0) -> Scaling:
    """Time per NN operation and per RRT iteration near each tree size."""
    rng = np.random.default_rng(seed)
    top = max(sizes) + WINDOW + 1
    nn = NearestNeighbors(DIM)
    pts = rng.random((top, DIM))
    stamps = np.empty(top)
    for i in range(top):
        nn.nearest(pts[i]) if len(nn) else None
        nn.add(pts[i])
        stamps[i] = time.perf_counter()
    nn_us = _windows(stamps, sizes)

    space = ConfigSpace(tuple(f"q{i}" for i in range(DIM)), np.zeros(DIM), np.ones(DIM))
    checker = _ToyChecker()
    region = ConfigRegion(id="corner", interpretation="toy", object="corner", lower=(0.9,) * DIM, upper=(1.0,) * DIM)
    settings = PlannerSettings(goal_bias=0.0, step_size=0.05, time_limit=600.0, max_iterations=top, initial_goal_samples=1)
    result = solve(space, checker, ConfigGoalSource((region,), space, checker), np.full(DIM, 0.05), settings, rng, seed=seed)
    # Edges into the ball are rejected, so tree size lags iterations slightly; index by iteration.
    rrt_us = _windows(np.array(checker.stamps), sizes)
    assert result.iterations >= top - 1
    return Scaling(tuple(sizes), tuple(nn_us), tuple(rrt_us))


def report(s: Scaling) -> str:
    lines = ["| tree size | NN add+nearest (us) | RRT iteration (us) |", "|---|---|---|"]
    for n, a, b in zip(s.sizes, s.nn_us, s.rrt_us):
        lines.append(f"| {n:,} | {a:.1f} | {b:.1f} |")
    lines.append("")
    lines.append(f"Growth from {s.sizes[0]:,} to {s.sizes[-1]:,} nodes: NN x{s.ratio('nn_us'):.2f}, RRT iteration x{s.ratio('rrt_us'):.2f} (target < 2).")
    return "\n".join(lines) + "\n"


def plot(s: Scaling, path, dpi: int = 110) -> None:
    """Microseconds per NN operation and per RRT iteration against tree size (log x)."""
    from lazyground.bench.tables import pyplot

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5, 3.4))
    ax.plot(s.sizes, s.rrt_us, marker="o", label="RRT iteration")
    ax.plot(s.sizes, s.nn_us, marker="s", label="NN add + nearest")
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("tree size (nodes)")
    ax.set_ylabel("µs")
    ax.set_title(f"growth x{s.ratio('rrt_us'):.2f} from {s.sizes[0]:,} to {s.sizes[-1]:,} nodes", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.4)
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
