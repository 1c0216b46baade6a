"""Ctrl-C before the work starts: end at once with one line and exit 130 (see :mod:`lazyground.entry`)."""

from __future__ import annotations

import os
import signal

EXIT_INTERRUPTED = 130


def exit_at_once(signum, frame) -> None:
    """A SIGINT handler for the imports: no KeyboardInterrupt inside half-imported numpy or pydrake."""
    os.write(2, b"interrupted\n")
    os._exit(EXIT_INTERRUPTED)


def work_begins() -> None:
    """From here on Ctrl-C raises KeyboardInterrupt again (the planner reports partial results)."""
    if signal.getsignal(signal.SIGINT) is exit_at_once:
        signal.signal(signal.SIGINT, signal.default_int_handler)
