"""Every setting, declared once: a field of a frozen dataclass, with its type, default, allowed values,
one-line doc and layers in the field's metadata (:func:`setting`).

One run's settings are a :class:`RunSettings` composed of :class:`PlannerSettings` (the search),
:class:`GoalSamplingSettings` (goal sources and IK), :class:`MotionSettings` (shortcutting and
timing after the solve) and :class:`TaskSettings`; :class:`SceneKeys` declares the scene's other
``planner:`` keys. :data:`SETTINGS` collects the declarations, and everything else derives from it:

* every settings class checks its fields on construction (:meth:`Setting.coerce`),
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
import typing
from dataclasses import dataclass
from typing import Any


class Strategy(enum.StrEnum):
    """Goal-selection strategies (paper Sec. III-B); registry: ``planning.strategies.STRATEGIES``."""

    REWARD_PENALTY = "reward-penalty"
    CONSECUTIVE = "consecutive"
    RANDOM = "random"
    COVER = "cover"  # reward-penalty covering the regions as samples get stuck (planning/cover.py, issue #33)
    COVER_CONNECT = "cover-connect"  # cover, and the strategy's goal tree connects to each new start node (#33)


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
        if self.type is bool:
            return "true, false"
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
        if self.type is bool:
            return None if isinstance(value, bool) else f"expected true or false, got {value!r}"
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
_API = frozenset({Layer.API})


class Objective(enum.StrEnum):
    """Which solution a run returns (issue #30); ``lazyground/tasks/anytime.py``."""

    FIRST = "first"  # the first one found (the paper's planner)
    SHORTEST = "shortest"  # the shortest shortened path found within the budget
    FASTEST = "fastest"  # the shortest trajectory duration found within the budget


class IKSolver(enum.StrEnum):
    """How IK goal sampling solves (lazyground/drake/ik.py)."""

    BATCH = "batch"  # numpy damped least squares, many attempts at once
    SNOPT = "snopt"  # one Drake InverseKinematics program per restart
    IPOPT = "ipopt"


def setting(default, doc: str, layers: frozenset[Layer], *, low: float | None = None, high: float | None = None,
            low_open: bool = False, optional: bool = False, default_doc: str | None = None):
    """A settings dataclass field declared with its doc, layers and range (kept in the field's metadata).

    The field's name and type come from the class; :data:`SETTINGS` collects every declared field.
    """
    meta = dict(doc=doc, layers=frozenset(layers), low=low, high=high, low_open=low_open, optional=optional,
                default_doc=default_doc)
    return dataclasses.field(default=default, metadata={"setting": meta})


def _coerce_fields(self) -> None:
    """Convert a settings object's declared fields in place (frozen: once, so every later read is typed)."""
    for f in dataclasses.fields(self):
        if "setting" in f.metadata:
            object.__setattr__(self, f.name, BY_NAME[f.name].coerce(getattr(self, f.name)))


MAX_FINE_CHECKS_PER_STEP = 100_000  # configurations the fine re-check tests along an edge of step_size (default 100)


@dataclass(frozen=True)
class PlannerSettings:
    """Settings of the reward-penalty RRT (defaults as in the authors' code); checked on construction."""

    strategy: Strategy = setting(Strategy.REWARD_PENALTY, "goal-selection strategy", _EVERYWHERE | {Layer.BENCH})
    algorithm: Algorithm = setting(
        Algorithm.RRT,
        "`rrt`: one tree from the start (the paper's Algorithm 1); `bidirectional`: a start tree and a goal "
        "tree per goal sample, the strategy choosing which goal tree grows in a fraction `goal_bias` of the "
        "goal turns (`lazyground/planning/birrt.py`)", _EVERYWHERE | {Layer.BENCH})
    goal_bias: float = setting(0.05, "probability of a goal-biased extension", _EVERYWHERE | {Layer.BENCH},
                               low=0.0, high=1.0)
    step_size: float = setting(0.5, "the longest extension ε, in the space's metric",
                               _EVERYWHERE | {Layer.PER_ALGORITHM}, low=0.0, low_open=True)
    edge_resolution: float | None = setting(
        None, "spacing of the collision checks along an edge; every returned path is re-checked at "
        "`validation_factor` times finer", _PLANNER | {Layer.PER_ALGORITHM}, low=0.0, low_open=True, optional=True,
        default_doc="`step_size / 10`")
    goal_extension: GoalExtension = setting(
        GoalExtension.PARTIAL,
        "the one-tree planner's goal-biased step: `partial` keeps the free part of a blocked step and counts "
        "it as a reward if it moved at all (the authors' MoveIt planner, OMPL's `checkMotion` with a last "
        "valid state); `extend` is one step, all or nothing; `connect` repeats free steps until blocked",
        _EVERYWHERE | {Layer.PER_ALGORITHM})
    kinematics: Kinematics = setting(
        Kinematics.HOLONOMIC,
        "car scenes: `holonomic` (the paper's setup: the car slides and turns on the spot), `reeds-shepp` "
        "(forwards and reverse along curves no tighter than the minimum turning radius from "
        "`kinematics:` in `models/<robot>/robot.yaml`) or `dubins` (forwards only); returned car paths are "
        "sampled along the curves at most 0.1 m apart (`lazyground/planning/car.py`, docs/spaces.md)",
        _EVERYWHERE | {Layer.BENCH})
    time_limit: float = setting(10.0, "seconds", _EVERYWHERE | {Layer.BENCH}, low=0.0, low_open=True)
    objective: Objective = setting(
        Objective.FIRST, "`first`: return the first solution; `shortest` / `fastest`: keep planning to other goal "
        "regions and samples for `budget` seconds and return the shortest shortened path / the quickest trajectory "
        "(`lazyground/tasks/anytime.py`)", _EVERYWHERE | {Layer.BENCH})
    budget: float | None = setting(
        None, "seconds `shortest` / `fastest` keep planning after the first solution (within `time_limit`)",
        _EVERYWHERE | {Layer.BENCH}, low=0.0, optional=True, default_doc="the first solution's planning time")
    improve_rounds: int = setting(8, "`shortest` / `fastest`: searches after the first solution, at most",
                                  _API, low=0.0)
    max_iterations: int = setting(10_000_000, "iterations before giving up", _PLANNER, low=0.0, low_open=True)
    initial_goal_samples: int = setting(10, "goal samples drawn before the search starts",
                                        _PLANNER | {Layer.PER_ALGORITHM}, low=0.0, low_open=True)
    resample_threshold: float = setting(0.2, "a penalised weight below this draws more samples",
                                        _PLANNER | {Layer.PER_ALGORITHM}, low=0.0, high=1.0)
    resample_count: int = setting(10, "samples added per resampling", _PLANNER | {Layer.PER_ALGORITHM},
                                  low=0.0, low_open=True)
    validation_factor: float = setting(10.0, "returned paths are re-checked at `edge_resolution` / this", _API,
                                       low=1.0)
    # trying 3 nearest nodes instead of 1 cut the mean iterations by 19-25 % on fetch_cans_1 / cans_2 / boxes_3 and
    # the mean CPU time by 5-7 % (120 seeds each, paired, interleaved; #19)
    connect_from: int = setting(3, "the two-tree planner's greedy connection starts from this many of the tree's "
                                "nearest nodes in turn, until one reaches the new node", _API, low=0.0, low_open=True)

    def __post_init__(self) -> None:
        _coerce_fields(self)
        fine = self.step_size * self.validation_factor / self.resolution
        if fine > MAX_FINE_CHECKS_PER_STEP:  # 2e10 configurations per edge (edge_resolution 1e-9) ran out of memory
            finest = self.step_size * self.validation_factor / MAX_FINE_CHECKS_PER_STEP
            raise ValueError(f"edge_resolution: {self.resolution:g} is too fine for step_size {self.step_size:g}: the "
                             f"re-check of one edge would test {fine:.3g} configurations (at most "
                             f"{MAX_FINE_CHECKS_PER_STEP:,}); give edge_resolution >= {finest:.3g}")

    @property
    def resolution(self) -> float:
        """The collision-check spacing along edges: ``edge_resolution``, default ``step_size / 10``."""
        return self.edge_resolution if self.edge_resolution is not None else self.step_size / 10.0


@dataclass(frozen=True)
class GoalSamplingSettings:
    """How goal sources turn goal regions into valid goal configurations (lazyground/goals.py, drake/ik.py)."""

    give_up_after: int = setting(50, "attempts on a goal region without one valid sample before it is given up",
                                 _API, low=0.0, low_open=True)
    attempts_per_sample: int = setting(10, "attempts one draw may make per goal sample it asks for", _API,
                                       low=0.0, low_open=True)
    ik_restarts: int = setting(3, "IK solves per attempt, each from another random start (workspace regions)",
                               _API, low=0.0, low_open=True)
    goal_learning: float = setting(0.75, "share of a goal region's draws that follow where its earlier draws "
                                   "worked (IK reached, collision-free); 0: uniform draws (lazyground/regions/learned.py)",
                                   _API, low=0.0, high=1.0)
    reach_prior: bool = setting(True, "drop the goal regions the robot provably cannot reach: a car's disc inscribed "
                                "in its footprint, or a ball inscribed in an arm's hand, finds no way there from the "
                                "start among the obstacles (`lazyground/planning/reach_prior.py`; `false`: sample "
                                "every region)", _EVERYWHERE)
    ik_solver: IKSolver = setting(IKSolver.BATCH, "IK solver: `batch` (numpy damped least squares, many attempts "
                                  "at once), `snopt` or `ipopt` (a Drake program per restart)", _API)

    def __post_init__(self) -> None:
        _coerce_fields(self)


@dataclass(frozen=True)
class MotionSettings:
    """After the solve (lazyground.motion, issue #16): shortcutting and time parameterisation."""

    shortcut_iterations: int = setting(100, "shortcut attempts after the solve (0: keep the raw path; "
                                       "`--no-shortcut`)", _MOTION, low=0.0)
    shortcut_time: float = setting(1.0, "seconds the shortcutting may take", _MOTION, low=0.0)
    # the bounds keep a trajectory within ~1,000 times the default's samples (a slower or denser one ran out of
    # memory: --speed 1e-6 asked for 3e9 samples on parking_1, --sample-rate 1e9 for 3e10)
    speed: float = setting(1.0, "trajectory speed s: velocity limits x s, acceleration limits x s²", _MOTION,
                           low=0.01, high=1.0)
    sample_rate: float = setting(100.0, "trajectory samples per second", _MOTION, low=0.0, high=1000.0,
                                 low_open=True)

    def __post_init__(self) -> None:
        _coerce_fields(self)


@dataclass(frozen=True)
class TaskSettings:
    """How a task shares its run between steps (lazyground/tasks/place.py, several.py)."""

    place_share: float = setting(0.4, "pick and place: the share of the time limit one placement attempt may "
                                 "use before the planner goes back for another object", _API, low=0.0, high=1.0,
                                 low_open=True)
    lift_min: float = setting(0.02, "pick and place: metres the gripper lifts the object at least (the lift stops at "
                              "the first clear height from here on)", _API, low=0.0)
    lift_max: float = setting(0.08, "pick and place: metres the lift may reach before the object counts as stuck",
                              _API, low=0.0, low_open=True)
    lift_step: float = setting(0.01, "pick and place: metres per IK step of the lift (each seeded by the last)", _API,
                               low=0.0, low_open=True)
    backtracks: int = setting(2, "several objects: how many times a step that finds no feasible choice may send the "
                              "planner back to re-plan the step before it with another placement "
                              "(`lazyground/tasks/several.py`)", _EVERYWHERE, low=0.0)
    placement_draws: int = setting(4, "several objects: candidate positions drawn per placement attempt while more "
                                   "objects follow; the one farthest from the surface's free-area centre is tried, to "
                                   "leave room (1: uniform; `lazyground/tasks/packing.py`)", _API, low=1.0)

    def __post_init__(self) -> None:
        _coerce_fields(self)


@dataclass(frozen=True)
class SceneKeys:
    """Keys of a scene's ``planner:`` block that are not a run's settings: its default seed, the world's padding."""

    seed: int = setting(0, "the default random seed", frozenset({Layer.SCENE, Layer.CLI, Layer.BENCH}), low=0.0)
    collision_padding: float = setting(0.0, "metres, robot–environment and robot–robot", frozenset({Layer.SCENE}),
                                       low=0.0)


@dataclass(frozen=True)
class RunSettings:
    """One run's settings: the planner's, goal sampling's, the motion's after the solve, the task's."""

    planner: PlannerSettings = dataclasses.field(default_factory=PlannerSettings)
    goal_sampling: GoalSamplingSettings = dataclasses.field(default_factory=GoalSamplingSettings)
    motion: MotionSettings = dataclasses.field(default_factory=MotionSettings)
    task: TaskSettings = dataclasses.field(default_factory=TaskSettings)

    @classmethod
    def of(cls, **values) -> "RunSettings":
        """Settings from flat names (``step_size=1.0, speed=0.5``), each routed to its group.

        Raises:
            ValueError: an unknown setting, or a value out of its range / choices.
        """
        unknown = sorted(set(values) - set(_GROUP_OF))
        if unknown:
            raise ValueError(f"unknown planner setting {unknown[0]!r} (known: {', '.join(_GROUP_OF)})")
        parts = {group: {} for group in _GROUPS}
        for name, value in values.items():
            parts[_GROUP_OF[name]][name] = value
        return cls(**{group: kind(**parts[group]) for group, kind in _GROUPS.items()})

    def replace(self, **values) -> "RunSettings":
        """A copy with flat-named settings changed (each in its group)."""
        out = {}
        for name, value in values.items():
            group = _GROUP_OF.get(name)
            if group is None:
                raise ValueError(f"unknown planner setting {name!r} (known: {', '.join(_GROUP_OF)})")
            out.setdefault(group, {})[name] = value
        return dataclasses.replace(self, **{g: dataclasses.replace(getattr(self, g), **v) for g, v in out.items()})


_GROUPS: dict[str, type] = {"planner": PlannerSettings, "goal_sampling": GoalSamplingSettings,
                            "motion": MotionSettings, "task": TaskSettings}  # RunSettings' fields
_GROUP_OF: dict[str, str] = {f.name: group for group, kind in _GROUPS.items() for f in dataclasses.fields(kind)}


def _declared_settings() -> tuple[Setting, ...]:
    """Every field declared with :func:`setting`, as a :class:`Setting` (in declaration order, scene keys after
    the planner's)."""
    out = []
    for kind in (PlannerSettings, SceneKeys, GoalSamplingSettings, MotionSettings, TaskSettings):
        hints = typing.get_type_hints(kind)
        for f in dataclasses.fields(kind):
            meta = f.metadata["setting"]
            typ = hints[f.name]
            base = next((t for t in typing.get_args(typ) if t is not type(None)), typ)
            out.append(Setting(f.name, base, f.default, meta["doc"], meta["layers"], meta["low"], meta["high"],
                               meta["low_open"], meta["optional"], meta["default_doc"]))
    return tuple(out)


SETTINGS: tuple[Setting, ...] = _declared_settings()
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


def from_scene(spec, **overrides) -> RunSettings:
    """The settings a run uses: the scene's ``planner:`` values, then its ``per_algorithm``
    values for the algorithm that will run, then the non-None ``overrides``.

    Args:
        spec: a scene's PlannerSpec (``scene.planner``).
        **overrides: settings by name (any group's: ``step_size``, ``speed``, ``ik_restarts``, ...);
            None means "not given".

    Raises:
        ValueError: an unknown setting name, or a value out of its range / choices.
    """
    unknown = sorted(set(overrides) - set(_GROUP_OF))
    if unknown:
        raise ValueError(f"unknown planner setting {unknown[0]!r} (known: {', '.join(_GROUP_OF)})")
    given = {k: v for k, v in overrides.items() if v is not None}
    values = {s.name: getattr(spec, s.name) for s in declared(Layer.API) if Layer.SCENE in s.layers}
    per = spec.per_algorithm.get(coerce("algorithm", given.get("algorithm", spec.algorithm)))
    if per is not None:
        values.update({s.name: getattr(per, s.name) for s in declared(Layer.PER_ALGORITHM)
                       if getattr(per, s.name) is not None})
    return RunSettings.of(**{**values, **given})


# --- the docs ---------------------------------------------------------------------------------------

def _shown_default(s: Setting) -> str:
    """A setting's default as the docs table shows it."""
    if s.type is bool:
        return f"`{str(s.default).lower()}`"
    return f"`{s.default}`" if s.choices else f"{s.default:,}" if s.type is int else f"{s.default:g}"


def markdown_table() -> str:
    """The ``planner:`` settings table of docs/scene_format.md and its ``per_algorithm`` keys."""
    rows = ["| key | default | allowed | meaning | also |", "| --- | --- | --- | --- | --- |"]
    for s in declared(Layer.SCENE):
        default = s.default_doc or _shown_default(s)
        allowed = ", ".join(f"`{c}`" for c in s.choices) if s.choices else s.allowed()
        also = ", ".join(f"`{s.flag}`" if layer is Layer.CLI else layer.value
                         for layer in (Layer.CLI, Layer.API, Layer.PER_ALGORITHM, Layer.BENCH) if layer in s.layers)
        rows.append(f"| `{s.name}` | {default} | {allowed} | {s.doc} | {also} |")
    keys = ", ".join(f"`{s.name}`" for s in declared(Layer.PER_ALGORITHM))
    rows += ["", f"`per_algorithm` (default none): settings that apply only when one algorithm runs: "
             f"`{{rrt: {{step_size: 2.65}}}}` (keys {keys}); the CLI's and API's own values still win."]
    rows += ["", "Settings of a run that a scene file does not hold (`api.plan(..., name=value)`; the CLI's flags "
             "where shown), each in its group of `lazyground.settings.RunSettings`:", "",
             "| name | group | default | allowed | meaning | also |", "| --- | --- | --- | --- | --- | --- |"]
    for s in declared(Layer.API):
        if Layer.SCENE not in s.layers:
            default = _shown_default(s)
            allowed = ", ".join(f"`{c}`" for c in s.choices) if s.choices else s.allowed()
            also = f"`{s.flag}`" if Layer.CLI in s.layers else ""
            rows.append(f"| `{s.name}` | {_GROUP_OF[s.name]} | {default} | {allowed} | {s.doc} | {also} |")
    return "\n".join(rows) + "\n"

