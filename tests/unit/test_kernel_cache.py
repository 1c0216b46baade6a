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
