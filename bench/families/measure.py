"""One command run as a whole process tree: wall seconds, CPU seconds and peak memory of the tree.

A solver that forks (gaitc's race of two orders, a child kept for ``--timeout``) spends CPU
and memory in processes the parent's own figures leave out, so each figure here covers the
whole tree:

- CPU: user + system seconds of the command and every descendant, as the change of
  ``getrusage(RUSAGE_CHILDREN)`` across the run.  That covers every process reaped inside
  the tree and the command itself, which this process reaps; to catch the descendants
  whose parent dies first, this process makes itself their reaper for the run
  (``PR_SET_CHILD_SUBREAPER``, Linux), so that they come to it and it reaps them too.
  When the command ends, what is left of its tree is killed and reaped.
- Memory: the peak of the sum of the resident sets of the tree's processes, sampled every
  :data:`SAMPLE` seconds from ``/proc/<pid>/stat`` (the tree is found from the parent field
  of every process, re-read every :data:`DISCOVER` seconds: this kernel has no
  ``/proc/<pid>/task/<tid>/children``); and ``ru_maxrss`` of the command (the largest
  resident set of the command and of the children it waited for), a lower bound of the
  peak that a process too short for a sample still sets.  Linux counts the pages of the
  process that forked a child in the child's ``ru_maxrss`` (the memory the ``exec``
  replaces is a copy of the parent's, or with vfork the parent's own), so a small solver
  started from this Python process would report this process's size.  The command is
  therefore started through GNU time (:data:`GNU_TIME`, a process of a megabyte or two),
  which reports the command's own figure; without it, ``ru_maxrss`` is read from ``wait4``
  as it is, and samples of a child that has not yet started its program (it still shows
  this process's command line) are left out.
- A time limit kills the command's process group, and any descendant that left it.

Linux only (``/proc``, ``prctl``); no dependency beyond the standard library.
"""

from __future__ import annotations

import contextlib
import ctypes
import functools
import os
import resource
import signal
import subprocess
import tempfile
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Final

#: Seconds between two samples of the tree's resident memory.
SAMPLE: Final = 0.01
#: Seconds between two searches of ``/proc`` for the tree's processes.
DISCOVER: Final = 0.05
#: GNU time, the launcher that reports the command's own ``ru_maxrss`` (see above).
GNU_TIME: Final = Path("/usr/bin/time")
#: The longest wait for the orphans of a finished command to come to be reaped.
REAP_WAIT: Final = 1.0
_PAGE: Final = os.sysconf("SC_PAGE_SIZE")
_PR_SET_CHILD_SUBREAPER: Final = 36
_MB: Final = 1024.0 * 1024.0
with open("/proc/self/cmdline", "rb") as _handle:
    _MY_COMMAND_LINE: Final = _handle.read()


@dataclass(frozen=True)
class Measurement:
    """One run of a command: its exit code (None when killed at the time limit), wall-clock
    seconds, CPU seconds of its process tree, the sampled peak of the tree's resident
    memory and ``ru_maxrss`` of the command (both MB), and what it printed."""

    returncode: int | None
    wall: float
    cpu: float
    peak_mb: float
    maxrss_mb: float
    stdout: str
    stderr: str

    @property
    def timed_out(self) -> bool:
        return self.returncode is None


def _stat(pid: int) -> tuple[int, int] | None:
    """``(parent pid, resident pages)`` of ``pid`` from ``/proc/<pid>/stat``; None once gone."""
    try:
        with open(f"/proc/{pid}/stat", "rb") as handle:
            text = handle.read()
    except OSError:
        return None
    fields = text[text.rfind(b")") + 2:].split()  # the name in brackets may hold spaces
    return int(fields[1]), int(fields[21])


def _parents() -> dict[int, list[int]]:
    """Each process's children, by parent pid (one pass over ``/proc``)."""
    out: dict[int, list[int]] = {}
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            found = _stat(int(entry))
            if found is not None:
                out.setdefault(found[0], []).append(int(entry))
    return out


def _tree(parents: dict[int, list[int]], roots: set[int]) -> set[int]:
    """``roots`` and every process descended from one of them."""
    out: set[int] = set()
    stack = list(roots)
    while stack:
        pid = stack.pop()
        if pid not in out:
            out.add(pid)
            stack.extend(parents.get(pid, ()))
    return out


def _resident(pids: set[int], started_only: bool) -> int:
    """Bytes resident in ``pids`` now (a zombie or a process gone counts nothing); with
    ``started_only``, a fork of this process that has not yet run its program counts
    nothing either."""
    pages = 0
    for pid in pids:
        found = _stat(pid)
        if found is not None and not (started_only and _is_me_before_exec(pid)):
            pages += found[1]
    return pages * _PAGE


def _is_me_before_exec(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as handle:
            return handle.read() == _MY_COMMAND_LINE
    except OSError:
        return False


def _subreaper(on: bool) -> bool:
    """Make this process the reaper of its orphaned descendants (or stop); False where the
    kernel refuses."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        return int(libc.prctl(_PR_SET_CHILD_SUBREAPER, int(on), 0, 0, 0)) == 0
    except (OSError, AttributeError):
        return False


def _children(parents: dict[int, list[int]] | None = None) -> set[int]:
    """This process's children (adopted orphans included), zombies too."""
    return set((parents if parents is not None else _parents()).get(os.getpid(), ()))


def _cpu(usage: resource.struct_rusage) -> float:
    return usage.ru_utime + usage.ru_stime


@functools.cache
def _gnu_time() -> str | None:
    """:data:`GNU_TIME` when it is GNU time (it takes ``-q -f %M -o FILE``), else None."""
    if not os.access(GNU_TIME, os.X_OK):
        return None
    try:
        said = subprocess.run([str(GNU_TIME), "--version"], capture_output=True, text=True,
                              timeout=10, check=False)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return str(GNU_TIME) if "GNU" in said.stdout + said.stderr else None


def measure(command: Sequence[str], timeout: float | None = None, *,
            cwd: str | Path | None = None, env: Mapping[str, str] | None = None) -> Measurement:
    """Run ``command`` and measure its process tree (see the module's docstring); past
    ``timeout`` seconds the tree is killed and the exit code is None."""
    launcher = _gnu_time()
    before = _children()
    adopted = _subreaper(True)
    start_usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err, \
            tempfile.NamedTemporaryFile(prefix="measure-", suffix=".rss") as rss:
        line = list(command)
        if launcher is not None:
            line = [launcher, "-q", "-f", "%M", "-o", rss.name, *line]
        began = time.perf_counter()
        proc = subprocess.Popen(line, stdin=subprocess.DEVNULL, stdout=out, stderr=err,
                                cwd=cwd, env=None if env is None else dict(env),
                                start_new_session=True)
        # the launcher's own few pages, or a fork of this process before its exec, are not
        # the command's
        skip = {proc.pid} if launcher is not None else set()
        deadline = None if timeout is None else began + timeout
        tree, peak, status, maxrss = {proc.pid}, 0, 0, 0
        next_search = began
        killed = False
        try:
            while True:
                now = time.perf_counter()
                if now >= next_search:
                    parents = _parents()
                    tree = _tree(parents, {proc.pid} | (_children(parents) - before))
                    next_search = now + DISCOVER
                peak = max(peak, _resident(tree - skip, launcher is None))
                pid, code, usage = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    status, maxrss = code, usage.ru_maxrss * 1024
                    break
                if deadline is not None and now > deadline:
                    _kill(proc.pid, tree)
                    _, status, usage = os.wait4(proc.pid, 0)
                    maxrss, killed = usage.ru_maxrss * 1024, True
                    break
                time.sleep(SAMPLE)
        except BaseException:  # Ctrl-C, or SIGTERM turned into SystemExit: end the tree too
            _kill(proc.pid, tree)
            with contextlib.suppress(ChildProcessError):
                os.wait4(proc.pid, 0)
            _finish(proc.pid, tree - {proc.pid}, before)
            if adopted:
                _subreaper(False)
            raise
        wall = time.perf_counter() - began
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        _finish(proc.pid, tree - {proc.pid}, before)
        if adopted:
            _subreaper(False)
        cpu = _cpu(resource.getrusage(resource.RUSAGE_CHILDREN)) - _cpu(start_usage)
        if launcher is not None:
            reported = Path(rss.name).read_text(encoding="utf-8").split()
            maxrss = int(reported[-1]) * 1024 if reported and reported[-1].isdigit() else 0
        out.seek(0)
        err.seek(0)
        stdout = out.read().decode("utf-8", errors="replace")
        stderr = err.read().decode("utf-8", errors="replace")
    return Measurement(None if killed else proc.returncode, wall, cpu,
                       max(peak, maxrss) / _MB, maxrss / _MB, stdout, stderr)


def _finish(group: int, known: set[int], before: set[int]) -> None:
    """Kill what is left of the tree (descendants the command did not wait for: ``known``,
    and any orphan adopted since) and reap whatever comes to this process, so that its CPU
    time counts; ``before`` are the children this process had before the run."""
    _kill(group, known | (_children() - before))
    waited_until = time.perf_counter() + REAP_WAIT
    while True:
        mine = _children() - before
        for pid in mine:
            with contextlib.suppress(ChildProcessError):
                os.waitpid(pid, os.WNOHANG)
        if not mine or time.perf_counter() > waited_until:
            return
        time.sleep(0.005)


def _kill(group: int, pids: set[int]) -> None:
    """SIGKILL the process group ``group`` and each of ``pids`` that is still in it or is
    this process's own child (a pid seen earlier may since belong to another process)."""
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(group, signal.SIGKILL)
    mine = _children()
    for pid in pids:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            if pid in mine or os.getpgid(pid) == group:
                os.kill(pid, signal.SIGKILL)
