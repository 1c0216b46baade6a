"""Strict, typed YAML → frozen dataclasses, in the spirit of Drake's ``yaml_load_typed``.

Unknown keys, missing required keys and wrong types are rejected with a
:class:`SceneError` whose one-line message names the file, the key path and the
problem, e.g. ``scene.yaml: objects[2].geometry.radius: must be > 0, got -1``.
"""

from __future__ import annotations

import dataclasses
import difflib
import functools
import re
import types
import typing
from typing import Any, Union, get_args, get_origin, get_type_hints

import yaml


INT_LIMIT = 2**63 - 1  # integers beyond 64 bits are never meaningful in a scene


class SceneError(ValueError):
    """A scene file that cannot be used; the message is one line."""


class _UniqueKeys:
    """Refuses a key given twice in one mapping (PyYAML keeps the last one silently); mixed into a loader."""

    def construct_mapping(self, node, deep=False):
        if isinstance(node, yaml.MappingNode):
            first: dict = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":  # '<<': keys it brings in may be overridden
                    continue
                key = self.construct_object(key_node, deep=True)
                try:
                    seen = key in first
                except TypeError:  # an unhashable key: SafeLoader's own error says so below
                    continue
                if seen:
                    raise yaml.constructor.ConstructorError(
                        None, None, f"duplicate key {key!r} (first at line {first[key]})", key_node.start_mark)
                first[key] = key_node.start_mark.line + 1
        return super().construct_mapping(node, deep)


class _UniqueKeyLoader(_UniqueKeys, yaml.SafeLoader):
    """``yaml.SafeLoader`` refusing duplicate keys (pure Python: its errors are the ones users see)."""


# libyaml's parser (~10x faster), when PyYAML was built with it. It composes nested collections
# recursively in C, without Python's recursion limit: text this short nests at most ~8k deep, far
# below what overflows the stack (100k did; 20k did not), so longer text keeps the Python parser.
_FAST_LOADER = type("_UniqueKeyCLoader", (_UniqueKeys, yaml.CSafeLoader), {}) if hasattr(yaml, "CSafeLoader") else None
FAST_YAML_MAX_CHARS = 16 * 1024


def load_yaml(text: str):
    """``yaml.safe_load`` that also refuses duplicate keys (a ``yaml.YAMLError`` naming the key and both lines).

    Empty documents after a ``---`` are ignored (``ros2 topic echo`` ends a message with one); two
    documents with content are a ``yaml.YAMLError``. Short text is parsed by libyaml when available;
    text it refuses is parsed again by PyYAML's own parser, so an error reads the same either way."""
    docs = None
    if _FAST_LOADER is not None and len(text) <= FAST_YAML_MAX_CHARS:
        try:
            docs = [d for d in yaml.load_all(text, Loader=_FAST_LOADER) if d is not None]
        except yaml.YAMLError:
            docs = None
    if docs is None:
        docs = [d for d in yaml.load_all(text, Loader=_UniqueKeyLoader) if d is not None]
    if len(docs) > 1:
        raise yaml.composer.ComposerError(None, None, f"{len(docs)} YAML documents separated by '---'; give one", None)
    return docs[0] if docs else None


def _fail(path: str, problem: str) -> typing.NoReturn:
    raise SceneError(f"{path}: {problem}" if path else problem)


def _type_name(tp) -> str:
    origin = get_origin(tp)
    if origin in (Union, types.UnionType):
        return " or ".join(_type_name(a) for a in get_args(tp) if a is not type(None))
    if origin in (list, tuple):
        return "list"
    if origin is dict:
        return "mapping"
    if dataclasses.is_dataclass(tp):
        return "mapping"
    return getattr(tp, "__name__", str(tp))


def convert(value: Any, tp, path: str):
    """Convert a parsed YAML value to ``tp``; raise SceneError naming ``path``."""
    origin = get_origin(tp)
    if tp is Any:
        return value
    if tp in (dict, list):  # untyped contents (e.g. grasp_types' per-type layout): check the container only
        if not isinstance(value, tp):
            _fail(path, f"expected {'a mapping' if tp is dict else 'a list'}, got {describe(value)}")
        return value
    if origin in (Union, types.UnionType):
        args = get_args(tp)
        if value is None and type(None) in args:
            return None
        options = [a for a in args if a is not type(None)]
        if len(options) == 1:  # Optional[X]: X's own error is the useful one
            return convert(value, options[0], path)
        same_kind = [a for a in options if _kind(a) == _kind_of(value)]
        if len(same_kind) == 1:  # e.g. a mapping for ``str | Spec``: the Spec's error is the useful one
            return convert(value, same_kind[0], path)
        for arg in options:
            try:
                return convert(value, arg, path)
            except SceneError:
                pass
        _fail(path, f"expected {_type_name(tp)}, got {describe(value)}")
    if dataclasses.is_dataclass(tp):
        return load_dataclass(value, tp, path)
    if origin is tuple:
        args = get_args(tp)
        if not isinstance(value, list):
            _fail(path, f"expected a list, got {describe(value)}")
        if len(args) == 2 and args[1] is Ellipsis:
            return tuple(convert(v, args[0], f"{path}[{i}]") for i, v in enumerate(value))
        if len(value) != len(args):
            _fail(path, f"expected a list of {len(args)} values, got {len(value)}")
        return tuple(convert(v, a, f"{path}[{i}]") for i, (v, a) in enumerate(zip(value, args)))
    if origin is dict:
        key_tp, val_tp = get_args(tp)
        if not isinstance(value, dict):
            _fail(path, f"expected a mapping, got {describe(value)}")
        return {convert(k, key_tp, path): convert(v, val_tp, f"{path}.{k}") for k, v in value.items()}
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            _fail(path, f"expected a number, got {describe(value)}")
        if isinstance(value, int) and abs(value) > INT_LIMIT:  # float() would raise OverflowError
            _fail(path, "number out of range")
        if value != value or value in (float("inf"), float("-inf")):
            _fail(path, "expected a finite number")
        return float(value)
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, int):
            _fail(path, f"expected an integer, got {describe(value)}")
        if abs(value) > INT_LIMIT:
            _fail(path, "number out of range")
        return value
    if tp is bool:
        if not isinstance(value, bool):
            _fail(path, f"expected true or false, got {describe(value)}")
        return value
    if tp is str:
        if not isinstance(value, str):
            _fail(path, f"expected a string, got {describe(value)}")
        return value
    raise TypeError(f"unsupported schema type {tp!r}")  # a schema bug, not a user error


def _kind(tp) -> str:
    """The YAML kind a schema type takes: mapping, list, string, number, boolean."""
    origin = get_origin(tp)
    if dataclasses.is_dataclass(tp) or tp is dict or origin is dict:
        return "mapping"
    if tp is list or origin in (list, tuple):
        return "list"
    return {str: "string", float: "number", int: "number", bool: "boolean"}.get(tp, "other")


def _kind_of(value) -> str:
    if isinstance(value, dict):
        return "mapping"
    if isinstance(value, list):
        return "list"
    if isinstance(value, bool):
        return "boolean"
    return "string" if isinstance(value, str) else "number" if isinstance(value, (int, float)) else "other"


def describe(value) -> str:
    if value is None:
        return "nothing"
    if isinstance(value, bool):
        return f"boolean {value}"
    if isinstance(value, (int, float)):
        return f"number {value}"
    if isinstance(value, str):
        short = value if len(value) <= 30 else value[:27] + "..."
        return f"string {short!r}"
    if isinstance(value, list):
        return "a list"
    if isinstance(value, dict):
        return "a mapping"
    return type(value).__name__


def load_dataclass(value: Any, cls, path: str):
    """Build dataclass ``cls`` from a mapping, rejecting unknown and missing keys.

    Field metadata may carry ``check``: a callable(value) returning an error
    string or None, applied after conversion.
    """
    if not isinstance(value, dict):
        _fail(path, f"expected a mapping, got {describe(value)}")
    hints = _type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}
    for key in value:
        if key not in fields:
            known = ", ".join(sorted(fields))
            close = difflib.get_close_matches(str(key), sorted(fields), n=1, cutoff=0.6)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            _fail(f"{path}.{key}" if path else str(key), f"unknown key{hint} (known keys: {known})")
    kwargs = {}
    for name, field in fields.items():
        sub = f"{path}.{name}" if path else name
        if name not in value:
            if field.default is dataclasses.MISSING and field.default_factory is dataclasses.MISSING:
                _fail(sub, "required key is missing")
            continue
        converted = convert(value[name], hints[name], sub)
        check = field.metadata.get("check")
        if check is not None and converted is not None:
            problem = check(converted)
            if problem:
                _fail(sub, problem)
        kwargs[name] = converted
    obj = cls(**kwargs)
    validate = getattr(obj, "validate", None)
    if validate is not None:
        problem = validate()
        if problem:
            key, _, message = problem.partition(": ")
            _fail(f"{path}.{key}" if path else key, message)
    return obj


@functools.lru_cache(maxsize=None)
def _type_hints(cls) -> dict:
    """``typing.get_type_hints`` of a dataclass, resolved once (it evaluates the annotations' strings each call)."""
    return get_type_hints(cls)


def positive(v) -> str | None:
    values = v if isinstance(v, tuple) else (v,)
    bad = [x for x in values if x <= 0]
    return f"must be > 0, got {bad[0]:g}" if bad else None


def non_negative(v) -> str | None:
    values = v if isinstance(v, tuple) else (v,)
    bad = [x for x in values if x < 0]
    return f"must be >= 0, got {bad[0]:g}" if bad else None


def in_range(lo: float, hi: float):
    def check(v) -> str | None:
        return None if lo <= v <= hi else f"must be in [{lo:g}, {hi:g}], got {v:g}"

    return check


def checked(check, **kwargs):
    """A dataclass field whose value must pass ``check``."""
    return dataclasses.field(metadata={"check": check}, **kwargs)


def line_of(text: str, path: str) -> int | None:
    """The 1-based line of the key a ``SceneError`` path names ("objects[2].type", "planer"), or None."""
    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except (yaml.YAMLError, RecursionError):  # (deep text libyaml parsed: PyYAML's composer recurses)
        return None
    line = None
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", path):
        if isinstance(node, yaml.SequenceNode) and part.startswith("["):
            i = int(part[1:-1])
            if i >= len(node.value):
                return line
            node = node.value[i]
            line = node.start_mark.line + 1
        elif isinstance(node, yaml.MappingNode):
            hit = next(((k, v) for k, v in node.value if str(getattr(k, "value", "")) == part), None)
            if hit is None:
                return line
            line, node = hit[0].start_mark.line + 1, hit[1]
        else:
            return line
    return line
