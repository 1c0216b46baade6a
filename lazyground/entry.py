"""The ``lazyground`` command's first lines: a Ctrl-C before the work starts is one line and exit 130.

Python and Drake take ~1-2 s to import; a KeyboardInterrupt raised inside a
half-imported numpy or pydrake surfaces as a long traceback (or an ImportError,
or CPython's own exit by SIGINT) that no ``except`` in ``cli.main`` sees. So the
entry point installs, before any heavy import, a handler that ends the process
at once; ``cli`` hands Ctrl-C back to Python (``work_begins``) right before the
planner runs, so a Ctrl-C there still returns partial statistics (the handler
lives in :mod:`lazyground.interrupt`, which both import). Only an
interrupt during the interpreter's own start-up (``site``, the first ~50 ms)
comes before this module and stays CPython's.
"""

from __future__ import annotations

import signal
import sys

from lazyground.interrupt import exit_at_once


def run() -> None:
    """The console script and ``python3 -m lazyground``."""
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:  # not when the shell made us ignore it
        signal.signal(signal.SIGINT, exit_at_once)
    from lazyground.cli import main

    sys.exit(main())
