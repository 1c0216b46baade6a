"""Self-collision set-up as MoveIt's setup assistant does it: sample, then allow what never matters.

:func:`sample_pairs` samples the robot's configurations (uniform within its limits, wrapping
and unbounded angles over one turn; a seeded generator) with the environment absent and
counts, for every pair of links with collision geometry the checker does not filter
already, how often they touch. :func:`allowed_pairs` turns the counts into MoveIt's three
reasons: ``Adjacent`` (links next to each other in the tree, links without geometry
skipped), ``Default`` (touching at the model's default configuration), ``Always`` (touching in at least ALWAYS of the samples: a modelling overlap, never
a real collision) and ``Never`` (never touching). :func:`write_allowed` writes them as a
scene's ``robot.allowed_collisions`` (YAML) or as an SRDF's ``disable_collisions``.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from pathlib import Path

import numpy as np
import yaml
from pydrake.geometry import Role

from lazyground.typed_yaml import SceneError

ALWAYS = 0.95  # the share of samples a pair must touch in to count as always colliding (MoveIt's default)
DEFAULT_SAMPLES = 1000


@dataclass(frozen=True)
class PairCounts:
    """How often each link pair touched over ``samples`` configurations (seeded by ``seed``)."""

    samples: int
    seed: int
    counts: dict[tuple[str, str], int]  # every candidate pair (unfiltered, both with geometry) -> touching samples
    adjacent: tuple[tuple[str, str], ...]
    default: tuple[tuple[str, str], ...] = ()  # touching at the model's default configuration (mimic joints followed)

    def always(self) -> list[tuple[str, str]]:
        return sorted(p for p, n in self.counts.items() if n >= ALWAYS * self.samples)

    def never(self) -> list[tuple[str, str]]:
        return sorted(p for p, n in self.counts.items() if n == 0)


def _pair(a: str, b: str) -> tuple[str, str]:
    return (a, b) if a <= b else (b, a)


def _links_with_geometry(diagram, plant, instance) -> set[str]:
    inspector = diagram.scene_graph().model_inspector()
    return {plant.get_body(b).name() for b in plant.GetBodyIndices(instance)
            if inspector.GetGeometries(plant.GetBodyFrameIdOrThrow(b), Role.kProximity)}


def adjacent_pairs(plant, instance, links: set[str]) -> list[tuple[str, str]]:
    """Links with geometry next to each other in the kinematic tree (through links without geometry)."""
    parent = {}
    for j in plant.GetJointIndices(instance):
        joint = plant.get_joint(j)
        parent[joint.child_body().name()] = joint.parent_body().name()
    out = set()
    for link in links:
        up = parent.get(link)
        while up is not None and up not in links:
            up = parent.get(up)
        if up is not None:
            out.add(_pair(link, up))
    return sorted(out)


def sample_pairs(checker, diagram, instance, samples: int, rng: np.random.Generator, seed: int, mimic=()) -> PairCounts:
    """Count touching link pairs over ``samples`` random configurations (see module docstring); ``mimic`` joints
    (``Mimic``) follow their leader in every sample, as the hardware's linkage holds them."""
    plant = checker.plant()
    links = _links_with_geometry(diagram, plant, instance)
    bodies = {n: plant.GetBodyByName(n, instance) for n in links}
    candidates = [p for p in combinations(sorted(links), 2)
                  if not checker.IsCollisionFilteredBetween(bodies[p[0]], bodies[p[1]])]
    counts = dict.fromkeys(candidates, 0)
    lower, upper = plant.GetPositionLowerLimits(), plant.GetPositionUpperLimits()
    lower = np.where(np.isfinite(lower), lower, -np.pi)
    upper = np.where(np.isfinite(upper), upper, np.pi)
    follow = [(plant.GetJointByName(m.joint, instance).position_start(), plant.GetJointByName(m.leader, instance).position_start(),
               m.multiplier, m.offset) for m in mimic if plant.HasJointNamed(m.joint, instance) and plant.HasJointNamed(m.leader, instance)]

    def touching(q: np.ndarray) -> set[tuple[str, str]]:
        for i, j, multiplier, offset in follow:
            q[i] = multiplier * q[j] + offset
        clearance = checker.CalcRobotClearance(q, 0.0)
        return {_pair(plant.get_body(a).name(), plant.get_body(b).name())
                for a, b, d in zip(clearance.robot_indices(), clearance.other_indices(), clearance.distances()) if d <= 0.0} & set(counts)

    for _ in range(samples):
        for p in touching(lower + (upper - lower) * rng.random(len(lower))):
            counts[p] += 1
    default = touching(plant.GetPositions(plant.CreateDefaultContext()).copy())
    return PairCounts(samples, seed, counts, tuple(adjacent_pairs(plant, instance, links)), tuple(sorted(default)))


def allowed_pairs(counts: PairCounts) -> list[tuple[str, str, str]]:
    """(link, link, reason) for every pair to stop checking: Adjacent, Default, Always, Never."""
    out = {p: "Adjacent" for p in counts.adjacent}
    out.update({p: "Default" for p in counts.default if p not in out})
    out.update({p: "Always" for p in counts.always() if p not in out})
    out.update({p: "Never" for p in counts.never() if p not in out})
    return sorted((a, b, r) for (a, b), r in out.items())


def write_allowed(path: str | Path, robot_name: str, counts: PairCounts) -> int:
    """Write the allowed pairs to ``path``: an SRDF when it ends in .srdf, else YAML for a scene's robot block.

    Returns:
        How many pairs were written.
    Raises:
        SceneError: the file cannot be written.
    """
    path = Path(path)
    pairs = allowed_pairs(counts)
    header = f"check-robot --write-allowed: {counts.samples} samples, seed {counts.seed}; reasons as MoveIt's setup assistant"
    if path.suffix.lower() == ".srdf":
        lines = ['<?xml version="1.0"?>', f"<!-- {header.replace('--', '')} -->", f'<robot name="{robot_name}">']  # no -- in a comment
        lines += [f'  <disable_collisions link1="{a}" link2="{b}" reason="{r}"/>' for a, b, r in pairs]
        text = "\n".join(lines + ["</robot>", ""])
    else:
        by_reason = {r: [[a, b] for a, b, rr in pairs if rr == r] for r in ("Adjacent", "Default", "Always", "Never")}
        text = (f"# {header}\n# paste under the scene's robot: block; "
                + ", ".join(f"{len(v)} {k.lower()}" for k, v in by_reason.items()) + "\n"
                + yaml.safe_dump({"allowed_collisions": [p for v in by_reason.values() for p in v]}, default_flow_style=None))
    try:
        path.write_text(text)
    except OSError as exc:
        raise SceneError(f"--write-allowed {path}: cannot write it: {exc.strerror or exc}") from None
    return len(pairs)
