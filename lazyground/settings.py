"""Every planner setting, declared once: name, type, default, allowed values, one-line doc, layers.

Everything else derives from :data:`SETTINGS`:

* :class:`PlannerSettings` (the planner's frozen settings; validated on construction),
* the scene file's ``planner:`` block and its ``per_algorithm`` entries
  (:mod:`lazyground.scene.schema`),
* the ``lazyground plan`` flags (:func:`lazyground.cli_options.add_cli_options`) and the ``bench`` sweep checks,
* the API's overrides (``api.plan(scene, "park", step_size=1.0)``),
* the settings table in ``docs/scene_format.md`` (:func:`markdown_table`; a test keeps the
  file equal to it; ``python3 -m lazyground.settings`` prints it).

The names of strategies, algorithms and goal extensions are written here only, as
:class:`enum.StrEnum` members; the planner's registries are keyed by these members.
This module imports nothing heavy: loading a scene must not pull in numpy's planner,
scipy or pydrake.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import numbers
from dataclasses import dataclass
from typing import Any


class Strategy(enum.StrEnum):
    """Goal-selection strategies (paper Sec. III-B); registry: ``planning.strategies.STRATEGIES``."""

    REWARD_PENALTY = "reward-penalty"
    CONSECUTIVE = "consecutive"
    RANDOM = "random"


class Algorithm(enum.StrEnum):
    """Tree planners; registry: ``planning.rrt.ALGORITHMS``."""

    RRT = "rrt"  # Algorithm 1: one tree from the start
    BIDIRECTIONAL = "bidirectional"  # a start tree and a goal tree per goal sample (planning/birrt.py)


class GoalExtension(enum.StrEnum):
    """How the one-tree planner's goal-biased step goes."""

    PARTIAL = "partial"  # keep the free part of a blocked step (the authors' RRTGoalRegion)
    EXTEND = "extend"  # one step, all or nothing
    CONNECT = "connect"  # repeat free steps until blocked or there


class Kinematics(enum.StrEnum):
    """How a car moves between configurations; the spaces are in ``planning/car.py``."""

    HOLONOMIC = "holonomic"  # straight lines in (x, y, heading): the paper's sliding car
    REEDS_SHEPP = "reeds-shepp"  # forwards and reverse along curves no tighter than the turning radius
    DUBINS = "dubins"  # forwards only


class Layer(enum.StrEnum):
    """Where a setting can be given."""

    SCENE = "scene"  # the scene file's planner: block
    PER_ALGORITHM = "per_algorithm"  # planner.per_algorithm.<algorithm>: block
    API = "api"  # a PlannerSettings field: api.plan(..., name=value)
    CLI = "cli"  # a `lazyground plan --name` flag
    BENCH = "bench"  # a `lazyground bench` option (comma list when swept)


@dataclass(frozen=True)
class Setting:
    """One declared setting. ``low``/``high`` bound numbers (``low_open``: strictly above ``low``)."""

    name: str
    type: type  # float, int or a StrEnum
    default: Any
    doc: str
    layers: frozenset[Layer]
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    optional: bool = False  # None allowed (a derived default, told by default_doc)
    default_doc: str | None = None

    @property
    def choices(self) -> tuple[str, ...] | None:
        return tuple(m.value for m in self.type) if issubclass(self.type, enum.Enum) else None

    def allowed(self) -> str:
        """The allowed values, as the docs and error messages say them."""
        if self.choices:
            return ", ".join(self.choices)
        if self.low is not None and self.high is not None:
            return f"{'(' if self.low_open else '['}{self.low:g}, {self.high:g}]"
        if self.low is not None:
            return f"> {self.low:g}" if self.low_open else f">= {self.low:g}"
        return "any"

    def problem(self, value) -> str | None:
        """Why ``value`` is not allowed (one phrase, without the name), or None."""
        if value is None:
            return None if self.optional else "must be given"
        if self.choices:
            if value not in self.choices:  # StrEnum members compare equal to their value
                return f"unknown {self.name.replace('_', ' ')} {value!r} (known: {self.allowed()})"
            return None
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            return f"expected a number, got {value!r}"
        if self.type is int and not float(value).is_integer():
            return f"expected an integer, got {value!r}"
        if not math.isfinite(value):
            return f"must be finite, got {value!r}"
        too_low = self.low is not None and (value <= self.low if self.low_open else value < self.low)
        too_high = self.high is not None and value > self.high
        return f"must be {_range_phrase(self)}, got {value:g}" if too_low or too_high else None

    def coerce(self, value):
        """``value`` as this setting's type (a StrEnum member, float or int).

        Raises:
            ValueError: one line naming the setting and its allowed values.
        """
        problem = self.problem(value)
        if problem:
            raise ValueError(f"{self.name}: {problem}")
        if value is None:
            return None
        return self.type(value) if self.choices or self.type is not float else float(value)

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")


def _range_phrase(s: Setting) -> str:
    return f"in {s.allowed()}" if s.high is not None else s.allowed()


_PLANNER = frozenset({Layer.SCENE, Layer.API})
_EVERYWHERE = frozenset({Layer.SCENE, Layer.API, Layer.CLI})
_MOTION = frozenset({Layer.API, Layer.CLI})

SETTINGS: tuple[Setting, ...] = (
    Setting("strategy", Strategy, Strategy.REWARD_PENALTY, "goal-selection strategy",
            _EVERYWHERE | {Layer.BENCH}),
    Setting("algorithm", Algorithm, Algorithm.RRT,
            "`rrt`: one tree from the start (the paper's Algorithm 1); `bidirectional`: a start tree and a goal "
            "tree per goal sample, the strategy choosing which goal tree grows in a fraction `goal_bias` of the "
            "goal turns (`lazyground/planning/birrt.py`)", _EVERYWHERE | {Layer.BENCH}),
    Setting("goal_bias", float, 0.05, "probability of a goal-biased extension", _EVERYWHERE | {Layer.BENCH},
            low=0.0, high=1.0),
    Setting("step_size", float, 0.5, "the longest extension ε, in the space's metric",
            _EVERYWHERE | {Layer.PER_ALGORITHM}, low=0.0, low_open=True),
    Setting("edge_resolution", float, None, "spacing of the collision checks along an edge; every returned "
            "path is re-checked at `validation_factor` times finer", _PLANNER | {Layer.PER_ALGORITHM},
            low=0.0, low_open=True, optional=True, default_doc="`step_size / 10`"),
    Setting("goal_extension", GoalExtension, GoalExtension.PARTIAL,
            "the one-tree planner's goal-biased step: `partial` keeps the free part of a blocked step and counts "
            "it as a reward if it moved at all (the authors' MoveIt planner, OMPL's `checkMotion` with a last "
            "valid state); `extend` is one step, all or nothing; `connect` repeats free steps until blocked",
            _EVERYWHERE | {Layer.PER_ALGORITHM}),
    Setting("kinematics", Kinematics, Kinematics.HOLONOMIC,
            "car scenes: `holonomic` (the paper's setup: the car slides and turns on the spot), `reeds-shepp` "
            "(forwards and reverse along curves no tighter than the minimum turning radius from "
            "`kinematics:` in `models/<robot>/robot.yaml`) or `dubins` (forwards only); returned car paths are "
            "sampled along the curves at most 0.1 m apart (`lazyground/planning/car.py`)",
            _EVERYWHERE | {Layer.BENCH}),
    Setting("time_limit", float, 10.0, "seconds", _EVERYWHERE | {Layer.BENCH}, low=0.0, low_open=True),
    Setting("max_iterations", int, 10_000_000, "iterations before giving up", _PLANNER, low=0.0, low_open=True),
    Setting("seed", int, 0, "the default random seed", frozenset({Layer.SCENE, Layer.CLI, Layer.BENCH}), low=0.0),
    Setting("initial_goal_samples", int, 10, "goal samples drawn before the search starts",
            _PLANNER | {Layer.PER_ALGORITHM}, low=0.0, low_open=True),
    Setting("resample_threshold", float, 0.2, "a penalised weight below this draws more samples",
            _PLANNER | {Layer.PER_ALGORITHM}, low=0.0, high=1.0),
    Setting("resample_count", int, 10, "samples added per resampling", _PLANNER | {Layer.PER_ALGORITHM},
            low=0.0, low_open=True),
    Setting("validation_factor", float, 10.0, "returned paths are re-checked at `edge_resolution` / this",
            frozenset({Layer.API}), low=1.0),
    Setting("collision_padding", float, 0.0, "metres, robot–environment and robot–robot",
            frozenset({Layer.SCENE}), low=0.0),
    # after the solve (lazyground.motion, issue #16): shortcutting and time parameterisation
    Setting("shortcut_iterations", int, 100, "shortcut attempts after the solve (0: keep the raw path; "
            "`--no-shortcut`)", _MOTION, low=0.0),
    Setting("shortcut_time", float, 1.0, "seconds the shortcutting may take", _MOTION, low=0.0),
    # the bounds keep a trajectory within ~1,000 times the default's samples (a slower or denser one ran out of
    # memory: --speed 1e-6 asked for 3e9 samples on parking_1, --sample-rate 1e9 for 3e10)
    Setting("speed", float, 1.0, "trajectory speed s: velocity limits x s, acceleration limits x s²", _MOTION,
            low=0.01, high=1.0),
    Setting("sample_rate", float, 100.0, "trajectory samples per second", _MOTION, low=0.0, high=1000.0,
            low_open=True),
)
BY_NAME: dict[str, Setting] = {s.name: s for s in SETTINGS}


def declared(layer: Layer) -> tuple[Setting, ...]:
    """The settings exposed in ``layer``, in declaration order."""
    return tuple(s for s in SETTINGS if layer in s.layers)


def coerce(name: str, value):
    """``value`` checked and converted for setting ``name`` (see :meth:`Setting.coerce`).

    Raises:
        ValueError: an unknown setting, or a value out of its range / choices.
    """
    setting = BY_NAME.get(name)
    if setting is None:
        raise ValueError(f"unknown planner setting {name!r} (known: {', '.join(BY_NAME)})")
    return setting.coerce(value)


# --- PlannerSettings: generated from the API layer ---------------------------------------------

MAX_FINE_CHECKS_PER_STEP = 100_000  # configurations the fine re-check tests along an edge of step_size (default 100)


def _post_init(self) -> None:
    for s in declared(Layer.API):  # frozen: convert in place once, so every later read is typed
        object.__setattr__(self, s.name, s.coerce(getattr(self, s.name)))
    fine = self.step_size * self.validation_factor / _resolution(self)
    if fine > MAX_FINE_CHECKS_PER_STEP:  # 2e10 configurations per edge (edge_resolution 1e-9) ran out of memory
        finest = self.step_size * self.validation_factor / MAX_FINE_CHECKS_PER_STEP
        raise ValueError(f"edge_resolution: {_resolution(self):g} is too fine for step_size {self.step_size:g}: the re-check "
                         f"of one edge would test {fine:.3g} configurations (at most {MAX_FINE_CHECKS_PER_STEP:,}); "
                         f"give edge_resolution >= {finest:.3g}")


def _resolution(self) -> float:
    """The collision-check spacing along edges: ``edge_resolution``, default ``step_size / 10``."""
    return self.edge_resolution if self.edge_resolution is not None else self.step_size / 10.0


def _field_type(s: Setting):
    return s.type | None if s.optional else s.type


PlannerSettings = dataclasses.make_dataclass(
    "PlannerSettings",
    [(s.name, _field_type(s), dataclasses.field(default=s.default)) for s in declared(Layer.API)],
    frozen=True,
    namespace={"__module__": __name__, "__post_init__": _post_init, "resolution": property(_resolution),
               "__doc__": "Settings of the reward-penalty RRT (defaults as in the authors' code); "
                          "fields and checks from :data:`lazyground.settings.SETTINGS`."},
)


def from_scene(spec, **overrides) -> PlannerSettings:
    """The settings a run uses: the scene's ``planner:`` values, then its ``per_algorithm``
    values for the algorithm that will run, then the non-None ``overrides``.

    Args:
        spec: a scene's PlannerSpec (``scene.planner``).
        **overrides: PlannerSettings fields; None means "not given".

    Raises:
        ValueError: an unknown setting name, or a value out of its range / choices.
    """
    unknown = sorted(set(overrides) - {s.name for s in declared(Layer.API)})
    if unknown:
        raise ValueError(f"unknown planner setting {unknown[0]!r} (known: {', '.join(s.name for s in declared(Layer.API))})")
    given = {k: v for k, v in overrides.items() if v is not None}
    values = {s.name: getattr(spec, s.name) for s in declared(Layer.API) if Layer.SCENE in s.layers}
    per = spec.per_algorithm.get(coerce("algorithm", given.get("algorithm", spec.algorithm)))
    if per is not None:
        values.update({s.name: getattr(per, s.name) for s in declared(Layer.PER_ALGORITHM)
                       if getattr(per, s.name) is not None})
    return PlannerSettings(**{**values, **given})


# --- the docs ---------------------------------------------------------------------------------------

def markdown_table() -> str:
    """The ``planner:`` settings table of docs/scene_format.md and its ``per_algorithm`` keys."""
    rows = ["| key | default | allowed | meaning | also |", "| --- | --- | --- | --- | --- |"]
    for s in declared(Layer.SCENE):
        default = s.default_doc or (f"`{s.default}`" if s.choices else f"{s.default:,}" if s.type is int else f"{s.default:g}")
        allowed = ", ".join(f"`{c}`" for c in s.choices) if s.choices else s.allowed()
        also = ", ".join(f"`{s.flag}`" if layer is Layer.CLI else layer.value
                         for layer in (Layer.CLI, Layer.API, Layer.PER_ALGORITHM, Layer.BENCH) if layer in s.layers)
        rows.append(f"| `{s.name}` | {default} | {allowed} | {s.doc} | {also} |")
    keys = ", ".join(f"`{s.name}`" for s in declared(Layer.PER_ALGORITHM))
    rows += ["", f"`per_algorithm` (default none): settings that apply only when one algorithm runs: "
             f"`{{rrt: {{step_size: 2.65}}}}` (keys {keys}); the CLI's and API's own values still win."]
    return "\n".join(rows) + "\n"

