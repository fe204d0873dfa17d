"""Quiet CUDD's complaint about a BDD manager freed with nodes still referenced.

dd.cudd's ``BDD`` raises ``AssertionError("Still N nodes referenced upon shutdown.")``
from its deallocation when the garbage collector frees a manager and its functions
together, in whatever order it picks; Python reports such an error on standard error and
goes on, and Cython hands it to ``sys.excepthook`` first.  On Python 3.13 that happens
during runs, so 19 of the quick suite's tests saw the line among their messages (issue
61).  Nothing is lost but the manager's memory, which the process returns as it ends, so
the command line (:func:`gaitc.cli.main`) installs these hooks, which drop exactly that
report and pass every other to Python's own.
"""

from __future__ import annotations

import sys
from types import TracebackType


def quiet_cudd_teardown() -> None:
    """Install the two hooks (again: idempotent)."""
    sys.unraisablehook, sys.excepthook = _unraisable, _excepthook


def _unraisable(report: sys.UnraisableHookArgs) -> None:
    if not _cudd_teardown(report.exc_value):
        sys.__unraisablehook__(report)


def _excepthook(kind: type[BaseException], value: BaseException,
                trace: TracebackType | None) -> None:
    if not _cudd_teardown(value):
        sys.__excepthook__(kind, value, trace)


def _cudd_teardown(error: BaseException | None) -> bool:
    return isinstance(error, AssertionError) and "nodes referenced upon shutdown" in str(error)
