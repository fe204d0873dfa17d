"""Waiting until a gaitc process has reached its own code, for the tests that signal it.

A signal that arrives while Python itself starts up (before gaitc's ``main`` runs) ends the
process with Python's own traceback; no program can handle it, so the signal tests wait
until gaitc is importing its commands (the CUDD library is mapped) and time their delays
from there. On a loaded machine start-up alone can take longer than half a second.
"""

from __future__ import annotations

import subprocess
import time
from pathlib import Path


def wait_until_started(proc: subprocess.Popen[str], timeout: float = 60.0) -> None:
    """Return once ``proc`` has loaded dd's CUDD module (gaitc's ``main`` is running)."""
    maps = Path(f"/proc/{proc.pid}/maps")
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            if "cudd" in maps.read_text(encoding="utf-8", errors="replace"):
                return
        except OSError:
            return  # no /proc (not Linux): fall back to the plain delay
        time.sleep(0.01)
