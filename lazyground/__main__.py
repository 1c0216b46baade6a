"""``python3 -m lazyground`` is the ``lazyground`` command."""

from lazyground.entry import run

run()
