"""Long commands off the request loop: one piece of work in a child process, cancellable.

The repair command solves the spec, which takes seconds or minutes. :class:`ChildJob` runs
such work in a forked child (:func:`gaitc.diagnostics.processes.first_success`, the one
way gaitc runs work in children), watched from a thread, so that the request loop goes on
answering; the stages the work reports come back to the loop as they happen, and
:meth:`ChildJob.cancel` kills the child at once. Where no child can be forked the work
runs in the watching thread, and cancelling only drops its result.

A child is forked from a process with other threads (the reader, the analyses), and a
fork copies the import locks those threads hold: a child that then imports a module
another thread was importing waits for ever. So the watching thread first runs the job's
``prepare``, which imports in the server what the work will need (waiting there, harmlessly,
for an import under way), and the child imports nothing.
"""

from __future__ import annotations

import asyncio
import contextlib
import os
import signal
import threading
import time
import traceback
from collections.abc import Callable
from typing import Any

from gaitc.diagnostics.processes import can_fork, first_success, to_parent

#: What a job ends with: ``("ok", value)``, ``("raise", exception, traceback text)``,
#: ``("died", exit status)``, ``("timeout",)`` (first_success's outcomes) or
#: ``("cancelled",)``.
Outcome = tuple[Any, ...]
#: The work: called with the function that reports a stage (a few words) as it starts.
Work = Callable[[Callable[[str], None]], Any]


class ChildJob:
    """``work`` in a child process, for at most ``seconds``; ``on_stage`` is called on the
    loop with each stage the work reports."""

    def __init__(self, work: Work, seconds: float, on_stage: Callable[[str], None],
                 prepare: Callable[[], None] | None = None) -> None:
        self._work = work
        self._prepare = prepare
        self._seconds = seconds
        self._on_stage = on_stage
        self._lock = threading.Lock()
        self._pid: int | None = None  # the child's, once it has said it
        self._ended = False  # first_success has returned: the child is gone
        self.cancelled = False
        self._loop: asyncio.AbstractEventLoop | None = None
        self._result: asyncio.Future[Outcome] | None = None

    def start(self) -> asyncio.Future[Outcome]:
        """Start the work; the future is its outcome (``("cancelled",)`` at once when
        :meth:`cancel` is called)."""
        self._loop = asyncio.get_running_loop()
        self._result = self._loop.create_future()
        threading.Thread(target=self._watch, name="gaitc-lsp-job", daemon=True).start()
        return self._result

    def cancel(self) -> None:
        """Kill the child (on the loop): the outcome is ``("cancelled",)`` from now on."""
        with self._lock:
            self.cancelled = True
            if self._pid is not None and not self._ended:
                _kill(self._pid)
        if self._result is not None and not self._result.done():
            self._result.set_result(("cancelled",))

    # ------------------------------------------------------------------ the watcher
    def _watch(self) -> None:
        outcome: Outcome
        try:
            if self._prepare is not None:
                self._prepare()
            if self.cancelled:
                outcome = ("cancelled",)
            elif can_fork():
                _, outcome = first_success([self._in_child], time.monotonic() + self._seconds,
                                           setup=_announce, relay=self._relay)
            else:
                outcome = ("ok", self._work(self._stage_here))
        except Exception as err:
            outcome = ("raise", err, traceback.format_exc())
        finally:
            with self._lock:
                self._ended = True
        self._hand(self._settle, outcome)

    def _in_child(self) -> Any:
        return self._work(_stage_to_parent)

    def _relay(self, message: Any) -> None:
        """A message of the child (in the watching thread): its pid, or a stage."""
        if isinstance(message, tuple) and len(message) == 2 and message[0] == "pid":
            with self._lock:
                self._pid = int(message[1])
                if self.cancelled:
                    _kill(self._pid)
        elif isinstance(message, tuple) and len(message) == 2 and message[0] == "stage":
            self._hand(self._on_stage, str(message[1]))

    def _stage_here(self, words: str) -> None:
        self._hand(self._on_stage, words)

    def _hand(self, callback: Callable[..., None], *args: Any) -> None:
        loop = self._loop
        if loop is None:
            return
        with contextlib.suppress(RuntimeError):  # the loop has closed: the server is ending
            loop.call_soon_threadsafe(callback, *args)

    def _settle(self, outcome: Outcome) -> None:
        if self._result is not None and not self._result.done():
            self._result.set_result(("cancelled",) if self.cancelled else outcome)


def _announce() -> None:
    """In the child, first: tell the parent its pid, so that it can be cancelled."""
    to_parent(("pid", os.getpid()))


def _stage_to_parent(words: str) -> None:
    to_parent(("stage", words))


def _kill(pid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.kill(pid, signal.SIGKILL)
