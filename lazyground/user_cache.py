"""The user's cache folder for files lazyground derives once and reads back (expanded xacro, converted meshes,
the request grammar's parser tables): ``$LAZYGROUND_CACHE``, default ``~/.cache/lazyground``."""

from __future__ import annotations

import os
from pathlib import Path


def cache_dir(part: str) -> Path:
    """The folder for one kind of cached file (not created here)."""
    return Path(os.environ.get("LAZYGROUND_CACHE") or Path.home() / ".cache" / "lazyground") / part
