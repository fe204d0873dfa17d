"""The quit key of a command that prepares before it shows an app: ``q`` stops the preparation.

``gaitc play`` synthesizes its controller (or the environment's counter-strategy) before the
player opens, which takes seconds to minutes on a large robot. Inside :func:`quit_key`, a
terminal's keys are read without echo by a watcher thread; ``q`` (or ``Q``) makes the main
thread raise :class:`Quit` at its next bytecode, as Ctrl-C raises KeyboardInterrupt, so the
work unwinds as under Ctrl-C (its child processes are killed, nothing is half-written). The
terminal's settings are put back on leaving, whatever ends the block.

Elsewhere (no terminal on stdin, not the main thread, or no POSIX terminal control) the
block runs as it is and ``q`` has no meaning.
"""

from __future__ import annotations

import os
import select
import signal
import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType
from typing import Final

#: The keys that quit, and the longest wait of the watcher between looks at its stop flag.
QUIT_KEYS: Final = frozenset("qQ")
_POLL: Final = 0.1
#: The signal the watcher sends to its own process; only this block handles it.
_SIGNAL: Final = signal.SIGUSR1


class Quit(BaseException):
    """The user pressed ``q`` before the app opened.

    A BaseException, as KeyboardInterrupt is, so that no ``except Exception`` in library code
    swallows it halfway through."""


def _raise_quit(signum: int, frame: FrameType | None) -> None:
    raise Quit


@contextmanager
def quit_key() -> Iterator[bool]:
    """Within the block, ``q`` on the terminal raises :class:`Quit` in the main thread.

    Yields whether the key is watched (stdin is a terminal and this is the main thread)."""
    try:
        import termios
        import tty
    except ImportError:  # not POSIX
        yield False
        return
    if threading.current_thread() is not threading.main_thread() or not sys.stdin.isatty():
        yield False
        return
    fd = sys.stdin.fileno()
    saved = termios.tcgetattr(fd)
    previous = signal.signal(_SIGNAL, _raise_quit)
    stop = threading.Event()
    watcher = threading.Thread(target=_watch, args=(fd, stop), daemon=True)
    try:
        tty.setcbreak(fd)
        watcher.start()
        yield True
    finally:
        stop.set()
        if watcher.is_alive():
            watcher.join()
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)
        signal.signal(_SIGNAL, previous)


def _watch(fd: int, stop: threading.Event) -> None:
    """Read keys from ``fd`` until ``stop``; on a quit key signal the process once."""
    while not stop.is_set():
        ready, _, _ = select.select([fd], [], [], _POLL)
        if not ready:
            continue
        try:
            key = os.read(fd, 1).decode("ascii", "replace")
        except OSError:
            return
        if not key:  # end of input
            return
        if key in QUIT_KEYS:
            os.kill(os.getpid(), _SIGNAL)
            return
