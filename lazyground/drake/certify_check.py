"""The compiled certifier's claims against Drake's checker (#31): the test and tools/certifier_soundness.py."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lazyground.drake.compiled import COLLIDES


@dataclass(frozen=True)
class ConfigComparison:
    configs: int
    drake_free: int
    proven_free: int
    proven_colliding: int
    open: int
    wrong_free: int  # proven free, Drake colliding
    wrong_collides: int  # proven colliding, Drake free


@dataclass(frozen=True)
class EdgeComparison:
    edges: int
    free: int
    mismatches: int  # edge_free or edge_fraction not Drake's


def drake_free(world, q_full: np.ndarray) -> np.ndarray:
    """Drake's own answers (no certifier) at plant position rows."""
    return np.asarray(world.checker.drake.CheckConfigsCollisionFree(list(q_full), parallelize=False), bool)


def sample_configs(world, rng: np.random.Generator, n: int) -> np.ndarray:
    """n plant position rows: a third uniform, a third near contact (bisected down to ~1e-5 rad between a free
    and a colliding sample), a third along random straight segments (as an edge's steps)."""
    k = n // 3
    uniform = world.full(np.array([world.space.sample(rng) for _ in range(k)]))
    free = drake_free(world, uniform)
    a, b = uniform[free], uniform[~free]
    m = min(len(a), len(b))
    near = []
    if m:
        a, b = a[rng.integers(0, len(a), k // 17 + 1)], b[rng.integers(0, len(b), k // 17 + 1)]
        for _ in range(17):
            mid = (a + b) / 2
            ok = drake_free(world, mid)
            a[ok], b[~ok] = mid[ok], mid[~ok]
            near.append(mid)
    near = np.vstack(near)[:k] if near else np.zeros((0, uniform.shape[1]))
    rest = n - len(uniform) - len(near)
    ends = np.array([world.space.sample(rng) for _ in range(2 * (rest // 50 + 1))])
    t = np.linspace(0.0, 1.0, 50)[None, :, None]
    seg = (ends[0::2, None] + t * (ends[1::2] - ends[0::2])[:, None]).reshape(-1, ends.shape[1])[:rest]
    return np.vstack([uniform, near, world.full(seg)])


def compare_configs(world, rng: np.random.Generator, n: int) -> ConfigComparison:
    """The certifier's codes on :func:`sample_configs` rows against Drake's answers."""
    q = sample_configs(world, rng, n)
    code, _ = world.checker.compiled.certify(q)
    drake = drake_free(world, q)
    return ConfigComparison(len(q), int(drake.sum()), int((code == 0).sum()), int((code == COLLIDES).sum()),
                            int(((code != 0) & (code != COLLIDES)).sum()), int(((code == 0) & ~drake).sum()),
                            int(((code == COLLIDES) & drake).sum()))


def compare_edges(world, rng: np.random.Generator, n: int, resolution: float = 0.05) -> EdgeComparison:
    """``edge_free`` and ``edge_fraction`` of the certified checker against Drake's edge checks (a checker
    without certifier at ``resolution``) on n edges: half from random starts towards random ends at most
    1 rad long (as a planner steps), half whole random segments."""
    from lazyground.drake.checker import DrakeChecker
    from lazyground.drake.diagram import build_diagram

    diagram, robot = build_diagram(world.scene, world.attached, visual=False)
    plain = DrakeChecker(diagram, robot, world.coordinates, world.padding, resolution, certify=False)
    free = mismatches = 0
    for i in range(n):
        a, b = world.space.sample(rng), world.space.sample(rng)
        if i % 2 == 0:
            b, _ = world.space.steer(a, b, 1.0)
        ours = world.checker.edge_free(a, b, resolution)
        theirs = plain.edge_free(a, b, resolution)
        frac_ours = world.checker.edge_fraction(a, b, resolution)
        frac_theirs = plain.edge_fraction(a, b, resolution)
        free += theirs
        mismatches += (ours != theirs) + (abs(frac_ours - frac_theirs) > 1e-12)
    return EdgeComparison(n, free, int(mismatches))


def compare_sweeps(world, rng: np.random.Generator, n: int, step: float = 0.005) -> ConfigComparison:
    """The sweep's codes (:meth:`CompiledCertifier.sweep`, configurations in sequence) against Drake's answers,
    on n random straight segments stepped every ``step`` (a fine check's spacing) in one sequence: free runs
    proven from anchors up to where the segments enter obstacles."""
    ends = [world.space.sample(rng) for _ in range(2 * n)]
    q = world.full(np.vstack([world.space.discretize(a, b, step) for a, b in zip(ends[0::2], ends[1::2])]))
    code, _ = world.checker.compiled.sweep(q)
    drake = drake_free(world, q)
    return ConfigComparison(len(q), int(drake.sum()), int((code == 0).sum()), int((code == COLLIDES).sum()),
                            int(((code != 0) & (code != COLLIDES)).sum()), int(((code == 0) & ~drake).sum()),
                            int(((code == COLLIDES) & drake).sum()))


def compare_penetration(world, rng: np.random.Generator, n: int) -> ConfigComparison | None:
    """The kernel's penetration test (``certify_one`` with the padding as ``shift``, as ``config_unpadded_free``
    asks) on :func:`sample_configs` rows: its 0 against SceneGraph's penetration query (free: nothing penetrates),
    its COLLIDES (a padded collision) against Drake's checker; None where the checker does not ask that (paddings
    differ, see checker._candidates_all_checked)."""
    checker = world.checker
    if not checker.penetration_first:
        return None
    q = sample_configs(world, rng, n)
    code = np.array([checker.compiled.certify_one(row, checker.unpadded_shift)[0] for row in q])
    clear = np.array([not checker.penetrates(row) for row in q])
    padded = drake_free(world, q)
    return ConfigComparison(len(q), int(clear.sum()), int((code == 0).sum()), int((code == COLLIDES).sum()),
                            int(((code != 0) & (code != COLLIDES)).sum()), int(((code == 0) & ~clear).sum()),
                            int(((code == COLLIDES) & padded).sum()))
