"""The ``gaitc`` command (its console script) and ``python -m gaitc``.

Signals are handled from the first moment: the command line takes tens of milliseconds to
import (more on a loaded machine), and a Ctrl-C or SIGTERM in that time used to end in
Python's raw ``KeyboardInterrupt`` traceback (exit -2) or a silent death. :func:`main`
takes SIGINT and SIGTERM over before anything else of gaitc's is imported, so a signal
during the import ends the run as one during the work does: its one line and exit code
130 or 143 (:mod:`gaitc.cli` handles them from there on).
"""

import contextlib
import gc
import os
import signal
import sys
from types import FrameType

#: The exit codes and lines of :mod:`gaitc.cli` for a run a signal ended (ExitCode's
#: INTERRUPTED and TERMINATED; tests/cli/test_signals.py checks that they agree).
ENDINGS = {signal.SIGINT: (130, "gaitc: interrupted"),
           signal.SIGTERM: (143, "gaitc: terminated")}


class _Early(BaseException):
    """A signal that came while the command line was being imported."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


def _early(signum: int, frame: FrameType | None) -> None:
    raise _Early(signum)


def _ended(signum: int) -> int:
    code, line = ENDINGS[signal.Signals(signum)]
    print(line, file=sys.stderr)
    return code


def main() -> int:
    """Run the command line on ``sys.argv`` and return its exit code."""
    taken = {}
    for signum, usual in ((signal.SIGINT, signal.default_int_handler),
                          (signal.SIGTERM, signal.SIG_DFL)):
        if signal.getsignal(signum) is usual:  # not one the caller chose to ignore
            taken[signum] = signal.signal(signum, _early)
    try:
        try:
            from gaitc.cli import main as run
        finally:  # the command line takes Ctrl-C over where Python's own handler has it
            if signal.SIGINT in taken:
                signal.signal(signal.SIGINT, signal.default_int_handler)
        return run()  # it takes SIGTERM over too, and puts this module's handler back
    except _Early as early:
        return _ended(early.signum)
    except KeyboardInterrupt:  # in the moment between the two handlers
        return _ended(signal.SIGINT)
    finally:
        if signal.SIGTERM in taken:
            signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _exit(code: int) -> None:
    """Leave with ``code``."""
    if code in (ENDINGS[signal.SIGINT][0], ENDINGS[signal.SIGTERM][0]):
        # Under -m, CPython now and then ends a run whose KeyboardInterrupt gaitc handled by
        # killing itself with SIGINT at shutdown (exit -2 instead of 130): leave directly.
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(OSError, ValueError):
                stream.flush()
        os._exit(code)
    # The interpreter's exit still runs the atexit handlers and frees what reference
    # counts free as the modules go, but the garbage collector no longer walks every object
    # left (10 ms of a small ``gaitc check``, a tenth of its run); objects in reference
    # cycles are then left to the operating system, as os._exit above leaves everything.
    gc.freeze()
    sys.exit(code)


def command() -> None:
    """The console script ``gaitc``: :func:`main`, then leave as ``python -m gaitc`` does."""
    _exit(main())


if __name__ == "__main__":
    command()
