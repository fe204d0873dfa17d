"""``python -m gaitc``."""

import sys

from gaitc.cli import main

sys.exit(main())
