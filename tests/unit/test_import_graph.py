"""No import cycle between the modules of lazyground/ and grounding/, module-level or inside functions.

The graph is built with ``ast`` from every ``import`` statement anywhere in a module
(functions included, as those are cycles too, only deferred). ``import a.b.c`` and
``from a.b import c`` depend on module ``a.b.c`` when it exists, else on ``a.b``; importing
a package's submodule does not count as depending on the package's ``__init__``, which
Python runs first but which is a cycle only if it imports back.
"""

import ast
import functools
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("lazyground", "grounding")


def module_names() -> dict[str, Path]:
    out = {}
    for pkg in PACKAGES:
        for path in (ROOT / pkg).rglob("*.py"):
            parts = path.relative_to(ROOT).with_suffix("").parts
            out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return out


@functools.lru_cache(maxsize=None)
def parsed(path: Path) -> ast.AST:
    """A module's syntax tree, parsed once for every test here (read-only)."""
    return ast.parse(path.read_text())


def _resolve(name: str, modules) -> str | None:
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


def import_graph() -> dict[str, set[str]]:
    modules = module_names()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for mod, path in modules.items():
        package = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
        for node in ast.walk(parsed(path)):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    anchor = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                    base = f"{anchor}.{base}" if base else anchor
                targets = [f"{base}.{a.name}" for a in node.names]
            for t in targets:
                dep = _resolve(t, modules)
                if dep is not None and dep != mod:
                    graph[mod].add(dep)
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One cycle as a list of modules (first == last), or None; iterative DFS with colours."""
    colour = {m: 0 for m in graph}  # 0 new, 1 on the stack, 2 done
    for root in sorted(graph):
        if colour[root]:
            continue
        stack = [(root, iter(sorted(graph[root])))]
        colour[root] = 1
        while stack:
            node, deps = stack[-1]
            for dep in deps:
                if colour[dep] == 1:
                    path = [n for n, _ in stack]
                    return path[path.index(dep):] + [dep]
                if colour[dep] == 0:
                    colour[dep] = 1
                    stack.append((dep, iter(sorted(graph[dep]))))
                    break
            else:
                colour[node] = 2
                stack.pop()
    return None


def test_the_graph_is_built_from_every_import():
    graph = import_graph()
    assert "lazyground.tasks.reach" in graph["lazyground.api"]
    assert "lazyground.drake.world" in graph["lazyground.tasks.worlds"]  # a function-level import counts
    assert "grounding.model" in graph["lazyground.plan_report"]


def test_find_cycle_finds_a_planted_cycle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_no_import_cycle():
    cycle = find_cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_api_and_place_do_not_import_each_other():
    graph = import_graph()
    assert "lazyground.tasks.place" not in graph["lazyground.api"]
    assert "lazyground.api" not in graph["lazyground.tasks.place"]


# --- layers (#35) ------------------------------------------------------------------------------------
# The one table of the package tree's floors, lowest first (docs/architecture.md draws it): a module
# belongs to the layer of the longest prefix naming it; an import, module-level or in a function,
# only points to its own layer or one below.
LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("scene", ("lazyground.scene", "lazyground.robots", "lazyground.typed_yaml", "lazyground.geometry",
               "lazyground.settings", "lazyground.planner_spec", "lazyground.bundled", "lazyground.mesh_files",
               "lazyground.tolerance", "lazyground.interrupt", "lazyground.user_cache")),
    ("regions", ("lazyground.regions",)),
    ("grounding", ("grounding",)),
    ("planning", ("lazyground.planning",)),
    ("goals", ("lazyground.goals",)),
    ("drake", ("lazyground.drake",)),
    ("motion", ("lazyground.motion",)),
    ("tasks", ("lazyground.tasks", "lazyground.plan_report")),
    ("api", ("lazyground.api", "lazyground.report", "lazyground.moveit")),
    ("viz", ("lazyground.viz", "lazyground.outputs")),
    ("bench", ("lazyground.bench",)),
    ("cli", ("lazyground.cli", "lazyground.cli_options", "lazyground.entry", "lazyground.__main__",
             "lazyground.bench.cli", "lazyground.moveit.cli")),
)
LAYER_NAMES = tuple(name for name, _ in LAYERS)
ROOT_PACKAGES = ("lazyground",)  # an __init__ that imports nothing: the bottom floor


def layer_of(module: str) -> str | None:
    """The layer of ``module`` by its longest prefix in :data:`LAYERS`, or None when no prefix names it."""
    if module in ROOT_PACKAGES:
        return LAYER_NAMES[0]
    best, depth = None, -1
    for name, prefixes in LAYERS:
        for p in prefixes:
            if (module == p or module.startswith(p + ".")) and p.count(".") > depth:
                best, depth = name, p.count(".")
    return best


def unit_of(module: str) -> str:
    """The package (a folder) or top-level module a module belongs to, ``lazyground.scene.loader`` ->
    ``lazyground.scene``; a module the table lifts out of its package's layer (``bench.cli``) is its own."""
    parts = module.split(".")
    unit = ".".join(parts[:2]) if parts[0] == "lazyground" else parts[0]
    return unit if layer_of(module) == layer_of(unit) else module


def upward_imports(graph: dict[str, set[str]]) -> list[str]:
    rank = {name: i for i, name in enumerate(LAYER_NAMES)}
    return sorted(f"{m} ({layer_of(m)}) -> {d} ({layer_of(d)})" for m, deps in graph.items() for d in deps
                  if rank[layer_of(d)] > rank[layer_of(m)])


def test_every_module_has_a_layer():
    assert [m for m in import_graph() if layer_of(m) is None] == []
    assert layer_of("lazyground.bench.cli") == "cli" and layer_of("lazyground.bench.runner") == "bench"


def test_no_import_points_up_the_layers():
    assert upward_imports(import_graph()) == []


def test_the_layer_check_sees_an_upward_import():
    assert upward_imports({"lazyground.drake.diagram": {"lazyground.viz.style"}, "lazyground.viz.style": set()}) == [
        "lazyground.drake.diagram (drake) -> lazyground.viz.style (viz)"]


def test_no_cycle_between_packages():
    """Packages, not only modules, form no cycle: one a late import would hide (scene <-> robots, scene <-> moveit)."""
    units: dict[str, set[str]] = {}
    for m, deps in import_graph().items():
        units.setdefault(unit_of(m), set()).update(unit_of(d) for d in deps if unit_of(d) != unit_of(m))
    cycle = find_cycle(units)
    assert cycle is None, "package cycle: " + " -> ".join(cycle)


def test_no_late_import():
    """No import is marked as deferred to dodge a cycle."""
    late = [f"{p.relative_to(ROOT)}:{i}" for p in module_names().values()
            for i, line in enumerate(p.read_text().splitlines(), 1)
            if "import " in line and ("# late" in line or "imported here:" in line)]
    assert late == []


def _below_cli(module: str) -> bool:
    return layer_of(module) != "cli"


def test_the_library_never_prints_nor_parses_arguments():
    """print, argparse and ``add_argument`` live in the CLI layer; the library returns values and takes plain ones."""
    found = []
    for mod, path in module_names().items():
        if not _below_cli(mod):
            continue
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Call):
                f = node.func
                name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
                if name in ("print", "add_argument", "add_argument_group", "add_parser", "add_subparsers"):
                    found.append(f"{mod}:{node.lineno} {name}")
            elif isinstance(node, (ast.Import, ast.ImportFrom)):
                names = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                if "argparse" in names:
                    found.append(f"{mod}:{node.lineno} import argparse")
    assert found == []


def test_no_module_reaches_into_anothers_private_members():
    """``obj._name`` only on ``self``/``cls``, and no ``from module import _name``: a helper that needs
    another class's internals is on the wrong side of a boundary (ik_attempts.py did this before #35)."""
    found = []
    for mod, path in module_names().items():
        for node in ast.walk(parsed(path)):
            if isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
                owner = node.value
                if not (isinstance(owner, ast.Name) and owner.id in ("self", "cls", "os")):  # os._exit: public API
                    found.append(f"{mod}:{node.lineno} {ast.unparse(node)}")
            elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] in PACKAGES:
                found += [f"{mod}:{node.lineno} from {node.module} import {a.name}" for a in node.names if a.name.startswith("_")]
    assert found == []


def layers_markdown() -> str:
    """The layer table of docs/architecture.md, from :data:`LAYERS` (``python3 tests/unit/test_import_graph.py`` prints it)."""
    rows = ["| layer | modules (a prefix names a package or module and everything under it) |", "| --- | --- |"]
    for name, prefixes in LAYERS:
        rows.append(f"| {name} | {', '.join(f'`{p}`' for p in prefixes)} |")
    return "\n".join(rows) + "\n"


def test_docs_draw_the_layers_of_this_table():
    text = (ROOT / "docs" / "architecture.md").read_text()
    assert " < ".join(LAYER_NAMES) in text
    assert layers_markdown() in text, "docs/architecture.md: regenerate the table with python3 tests/unit/test_import_graph.py"


if __name__ == "__main__":
    print(layers_markdown(), end="")
