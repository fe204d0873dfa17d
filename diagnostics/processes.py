"""Work in forked child processes: the answer of the first child to succeed, within a deadline.

Used twice: :mod:`gaitc.isolation` runs one solver run in a child to make ``--timeout`` and
``--memory-limit`` hard limits, and :mod:`solver.portfolio` races two solver configurations
and keeps the first answer. Each child sends back one outcome through a pipe:
``("ok", value)`` or ``("raise", exception, traceback text)``; a child that ends without
one is ``("died", exit status)``, and a deadline passed is ``("timeout",)``. Children die
with their parent (``PR_SET_PDEATHSIG`` on Linux), ignore Ctrl-C (the parent handles it and
kills them), and are killed once an answer is chosen.
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing
import os
import signal
import time
import traceback
from collections.abc import Callable, Sequence
from multiprocessing.connection import Connection
from typing import Any, Final

Outcome = tuple[Any, ...]
_PR_SET_PDEATHSIG: Final = 1
_POLL: Final = 0.05  # seconds between looks at the children


def can_fork() -> bool:
    return hasattr(os, "fork")


def first_success(works: Sequence[Callable[[], Any]], deadline: float | None = None,
                  setup: Callable[[], None] | None = None) -> tuple[int, Outcome]:
    """Run each of ``works`` in its own forked child (after ``setup`` there) and return the
    index and outcome of the first to answer ``ok``; when none does, the first other
    outcome. ``deadline`` is a :func:`time.monotonic` time: past it, ``("timeout",)``."""
    context = multiprocessing.get_context("fork")
    children = []
    for work in works:
        receiver, sender = context.Pipe(duplex=False)
        # Not daemonic: a child may race children of its own (solver.portfolio inside the
        # child of gaitc.isolation); every child is killed and joined below anyway.
        child = context.Process(target=_child, args=(work, setup, sender), daemon=False)
        child.start()
        sender.close()
        children.append((child, receiver))
    try:
        return _wait(children, deadline)
    finally:
        for child, receiver in children:
            if child.is_alive():
                child.kill()
            child.join()
            receiver.close()


def _wait(children: list[tuple[Any, Connection]], deadline: float | None
          ) -> tuple[int, Outcome]:
    failures: dict[int, Outcome] = {}
    while True:
        for index, (child, receiver) in enumerate(children):
            if index in failures:
                continue
            outcome = _outcome(child, receiver)
            if outcome is None:
                continue
            if outcome[0] == "ok":
                return index, outcome
            failures[index] = outcome
        if len(failures) == len(children):
            first = min(failures)
            return first, failures[first]
        if deadline is not None and time.monotonic() >= deadline:
            return 0, ("timeout",)
        time.sleep(_POLL)


def _outcome(child: Any, receiver: Connection) -> Outcome | None:
    """The child's answer, ``("died", status)`` when it ended without one, else None."""
    try:
        if receiver.poll(0):
            answer: Outcome = receiver.recv()
            return answer
    except EOFError:
        pass
    if child.is_alive():
        return None
    try:
        if receiver.poll(0):
            late: Outcome = receiver.recv()
            return late
    except EOFError:
        pass
    return ("died", child.exitcode)


def _child(work: Callable[[], Any], setup: Callable[[], None] | None,
           sender: Connection) -> None:
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent handles Ctrl-C and kills us
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    die_with_parent()
    try:
        if setup is not None:
            setup()
        outcome: Outcome = ("ok", work())
    except BaseException as err:  # every exception goes back to the parent
        outcome = ("raise", err, traceback.format_exc())
    try:
        sender.send(outcome)
    except Exception as err:  # an answer that cannot be pickled
        with contextlib.suppress(Exception):
            sender.send(("raise", RuntimeError(
                f"the answer could not be passed back: {type(err).__name__}: {err}"), ""))
    finally:
        sender.close()


def die_with_parent() -> None:
    """Ask the kernel to kill this process when its parent ends (Linux; elsewhere a no-op)."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        pass
