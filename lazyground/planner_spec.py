"""A scene's ``planner:`` block as a typed dataclass, derived from the declarations of :mod:`lazyground.settings`.

Below the scene and the robots: a scene's block and a robot.yaml's block are checked by the same type.
"""

from __future__ import annotations

from dataclasses import field, make_dataclass

from lazyground.settings import Algorithm, Layer, Setting, declared
from lazyground.typed_yaml import checked


def _spec_field(s: Setting, per_algorithm: bool):
    """A scene field for setting ``s``: names as str (the planner converts them), numbers checked."""
    tp = str if s.choices else s.type
    optional = per_algorithm or s.optional
    default = None if per_algorithm else s.default
    return (s.name, tp | None if optional else tp, checked(s.problem, default=default))


AlgorithmSpec = make_dataclass(
    "AlgorithmSpec", [_spec_field(s, True) for s in declared(Layer.PER_ALGORITHM)], frozen=True,
    namespace={"__module__": __name__, "__doc__": "Settings that apply only when one algorithm runs; keys left out keep the scene's."},
)


def _planner_problem(self) -> str | None:
    for name in self.per_algorithm:
        if name not in tuple(Algorithm):
            return f"per_algorithm.{name}: unknown algorithm (known: {', '.join(Algorithm)})"
    return None


PlannerSpec = make_dataclass(
    "PlannerSpec",
    [_spec_field(s, False) for s in declared(Layer.SCENE)]
    + [("per_algorithm", dict[str, AlgorithmSpec], field(default_factory=dict))],
    frozen=True,
    namespace={"__module__": __name__, "validate": _planner_problem, "__doc__": """Planner defaults for this scene; the CLI and API may override each.

    Fields come from :data:`lazyground.settings.SETTINGS` (scene layer). ``per_algorithm``
    holds settings for one algorithm only, e.g. the one-tree planner's longer step on the
    Fetch scenes: ``{rrt: {step_size: 2.65}}``.
    """},
)
