"""``python -m gaitc``."""

import contextlib
import os
import sys

from gaitc.cli import main
from gaitc.cli.exitcodes import ExitCode

code = main()
if code in (ExitCode.INTERRUPTED, ExitCode.TERMINATED):
    # Under -m, CPython now and then ends a run whose KeyboardInterrupt gaitc handled by
    # killing itself with SIGINT at shutdown (exit -2 instead of 130): leave directly.
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
    os._exit(code)
sys.exit(code)
