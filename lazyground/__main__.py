"""``python3 -m lazyground`` is the ``lazyground`` command."""

import sys

from lazyground.cli import main

sys.exit(main())
