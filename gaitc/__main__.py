"""``python -m gaitc``."""

import contextlib
import gc
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
# The interpreter's exit still runs the atexit handlers and frees what reference counts
# free as the modules go, but the garbage collector no longer walks every object left (10
# ms of a small ``gaitc check``, a tenth of its run); objects in reference cycles are then
# left to the operating system, as os._exit above leaves everything.
gc.freeze()
sys.exit(code)
