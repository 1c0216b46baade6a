"""numba keys a cached kernel on its own file's time stamp only: a kernel calling or inlining one from another
file would keep stale code when only that file changes. The caches live in a folder named by the text of every
kernel file, and every file that compiles with cache=True is one of them and selects that folder first."""

from __future__ import annotations

import hashlib
import re
from pathlib import Path

import lazyground
from lazyground.user_cache import KERNEL_SOURCES, use_kernel_cache

ROOT = Path(lazyground.__file__).resolve().parent


def test_every_cached_kernel_file_is_keyed():
    kernel = re.compile(r"@njit\(.*cache=True")
    cached = sorted(str(p.relative_to(ROOT)) for p in ROOT.rglob("*.py") if kernel.search(p.read_text()))
    assert cached == sorted(KERNEL_SOURCES)
    for name in KERNEL_SOURCES:
        text = (ROOT / name).read_text()
        assert "\nuse_kernel_cache()" in text
        assert text.index("\nuse_kernel_cache()") < kernel.search(text).start()


def test_the_cache_folder_names_the_text_of_every_kernel_file():
    digest = hashlib.sha1(b"".join((ROOT / f).read_bytes() for f in KERNEL_SOURCES)).hexdigest()[:16]
    folder = use_kernel_cache()
    assert Path(folder).name == f"numba-{digest}"
    import numba

    assert numba.config.CACHE_DIR == folder


def _row_test_copies() -> dict[str, int]:
    """Per compiled (not inlined) function of the sphere and edge kernels, how many copies of the row test
    (sphere_kernels.open_pairs_row) it holds, directly or through functions numba inlines into it (inline="always")."""
    import ast

    calls, inline = {}, set()
    for name in ("drake/sphere_kernels.py", "drake/edge_kernel.py"):
        for node in ast.parse((ROOT / name).read_text()).body:
            if isinstance(node, ast.FunctionDef):
                calls[node.name] = [c.func.id for c in ast.walk(node) if isinstance(c, ast.Call)
                                    and isinstance(c.func, ast.Name)]
                if any(isinstance(k, ast.keyword) and k.arg == "inline" for d in node.decorator_list
                       if isinstance(d, ast.Call) for k in d.keywords):
                    inline.add(node.name)

    def copies(f: str) -> int:
        return sum(1 if g == "open_pairs_row" else copies(g) if g in inline else 0 for g in calls.get(f, ()))

    counts = {f: copies(f) for f in calls if f not in inline}
    return {f: n for f, n in counts.items() if n}


def test_the_row_test_is_compiled_only_where_single_checks_need_it_inlined():
    # each copy of the row test costs ~20-30 s of the kernels' first compile (#31): one compiled copy that the
    # batch, sweep and first_open kernels call, and one inlined into each of a planner's single checks
    assert _row_test_copies() == {"row_code": 1, "edge_call": 1, "config_call": 1}
