"""``python -m plcsim``: the same as the ``plcsim`` command (where the script is not on PATH)."""

import sys

from plcsim.apps.cli import main

sys.exit(main())
