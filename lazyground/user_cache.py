"""The user's cache folder for files lazyground derives once and reads back (expanded xacro, converted meshes,
the request grammar's parser tables): ``$LAZYGROUND_CACHE``, default ``~/.cache/lazyground``."""

from __future__ import annotations

import functools
import hashlib
import os
from pathlib import Path


def cache_dir(part: str) -> Path:
    """The folder for one kind of cached file (not created here)."""
    return Path(os.environ.get("LAZYGROUND_CACHE") or Path.home() / ".cache" / "lazyground") / part


# The modules numba compiles with cache=True. numba keys a cached function on its own file's time stamp only,
# so a kernel that inlines or calls one from another of these files would keep the old code when only that
# file changes (a git pull, an upgrade): the caches live in a folder named by a hash of all of them instead.
KERNEL_SOURCES = ("drake/sphere_kernels.py", "drake/edge_kernel.py", "drake/ik/kernels.py", "planning/linear_kernels.py",
                  "planning/curves.py", "planning/car_kernels.py", "planning/topk.py",
                  "drake/approach_kernel.py")


@functools.lru_cache(maxsize=1)
def use_kernel_cache() -> str:
    """Point numba's on-disk cache at ``__pycache__/numba-<hash of KERNEL_SOURCES>`` in the package (or, where
    that is read-only, under :func:`cache_dir`); called by each kernel module before it defines its kernels.
    Returns the folder."""
    import numba

    root = Path(__file__).resolve().parent
    digest = hashlib.sha1(b"".join((root / f).read_bytes() for f in KERNEL_SOURCES)).hexdigest()[:16]
    for base in (root / "__pycache__", cache_dir("numba")):
        try:
            base.mkdir(parents=True, exist_ok=True)
        except OSError:
            continue
        if os.access(base, os.W_OK):
            numba.config.CACHE_DIR = str(base / f"numba-{digest}")
            break
    return numba.config.CACHE_DIR
