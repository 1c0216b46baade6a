"""No import cycle between the modules of lazyground/ and grounding/, module-level or inside functions.

The graph is built with ``ast`` from every ``import`` statement anywhere in a module
(functions included, as those are cycles too, only deferred). ``import a.b.c`` and
``from a.b import c`` depend on module ``a.b.c`` when it exists, else on ``a.b``; importing
a package's submodule does not count as depending on the package's ``__init__``, which
Python runs first but which is a cycle only if it imports back.
"""

import ast
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


def _resolve(name: str, modules) -> str | None:
    while name and name not in modules:
        name = name.rpartition(".")[0]
    return name or None


def import_graph() -> dict[str, set[str]]:
    modules = module_names()
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for mod, path in modules.items():
        package = mod if path.name == "__init__.py" else mod.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text())):
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
    assert "lazyground.place" not in graph["lazyground.api"]
    assert "lazyground.api" not in graph["lazyground.place"]
