"""The live status line of a long command: a solver's :class:`~gaitc.solver.progress.Stage`
events shown on the terminal in the user's words, with a bar and the time elapsed.

On a terminal, :class:`StatusLine` redraws one line of stderr (at most ten times a second,
and every half second by itself so that the clock moves during a long BDD operation) and
clears it when the work is done, so that the results print on a clean screen::

    solving the game: round 2, goal 1 of 2 (visit r11)  [#####-----]  12.4 s

With ``--verbose`` every change of stage prints as a line of its own, with the solver's
figures (rounds, BDD sizes); elsewhere (a pipe, a log file) nothing is shown.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Final, TextIO

from gaitc.api.progress import Progress, Stage
from gaitc.diagnostics.processes import mask_held

#: Width of the bar in characters, and the redraw rates in seconds.
BAR: Final = 10
REDRAW: Final = 0.1
TICK: Final = 0.5


class StatusLine:
    """A one-line display of the latest :class:`Stage` (call it with each event)."""

    def __init__(self, stream: TextIO, width: int = 100, note: str = "") -> None:
        self.stream = stream
        self.width = width
        self.note = note
        self.started = time.monotonic()
        self.stage: Stage | None = None
        self._drawn = 0.0
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._ticker = threading.Thread(target=self._tick, daemon=True)

    def __call__(self, stage: Stage) -> None:
        with self._lock:
            changed = self.stage is None or stage.words != self.stage.words
            self.stage = stage
            if changed or time.monotonic() - self._drawn >= REDRAW:
                self._draw()

    def start(self) -> None:
        self._ticker.start()

    def close(self) -> None:
        """Stop the clock and clear the line."""
        self._stop.set()
        if self._ticker.is_alive():
            self._ticker.join()
        with self._lock:
            if self._drawn:
                self.stream.write("\r" + " " * self.width + "\r")
                self.stream.flush()

    def line(self) -> str:
        """The text of the line for the current stage."""
        stage = self.stage
        if stage is None:
            return ""
        seconds = time.monotonic() - self.started
        bar = ""
        if stage.fraction is not None:
            done = max(0, min(BAR, round(stage.fraction * BAR)))
            bar = f"  [{'#' * done}{'-' * (BAR - done)}]"
        clock = f"  {seconds:.1f} s" + (f"  ({self.note})" if self.note else "")
        room = self.width - len(bar) - len(clock) - 1
        words = stage.words if len(stage.words) <= room else stage.words[:room - 3] + "..."
        return words + bar + clock

    def _draw(self) -> None:
        text = self.line()
        self.stream.write("\r" + text.ljust(self.width - 1))
        self.stream.flush()
        self._drawn = time.monotonic()

    def _tick(self) -> None:
        mask_held(True)  # signals go to the main thread, which holds them back around forks
        while not self._stop.wait(TICK):
            with self._lock:
                if self.stage is not None:
                    self._draw()


class StageLog:
    """``--verbose``: one line per change of stage or of its share done, with figures."""

    def __init__(self, stream: TextIO) -> None:
        self.stream = stream
        self.started = time.monotonic()
        self._last: tuple[str, float | None] | None = None

    def __call__(self, stage: Stage) -> None:
        key = (stage.words, stage.fraction)
        if key == self._last:
            return
        self._last = key
        seconds = time.monotonic() - self.started
        print(f"gaitc: {seconds:7.2f} s  {stage}", file=self.stream, flush=True)


@contextmanager
def progress_display(verbose: bool = False, stream: TextIO | None = None, note: str = ""
                     ) -> Iterator[Progress | None]:
    """The progress callback for a command: a :class:`StageLog` with ``verbose``, a
    :class:`StatusLine` on a terminal (cleared on leaving; ``note`` follows its clock, such
    as the key that quits), else None."""
    out = sys.stderr if stream is None else stream
    if verbose:
        yield StageLog(out)
        return
    if not out.isatty():
        yield None
        return
    status = StatusLine(out, note=note)
    status.start()
    try:
        yield status
    finally:
        status.close()
