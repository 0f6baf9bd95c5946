"""``python -m pvshadows``: the same as the ``pvshadows`` command."""

import sys

from pvshadows.tools.cli import main

sys.exit(main())
