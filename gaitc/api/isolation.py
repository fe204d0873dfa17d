"""Hard limits for one solver run: ``--timeout`` and ``--memory-limit`` that always hold.

The solver checks its deadline between fixpoint steps, but a single CUDD operation (or a
lowering, bit-blasting or extraction step) can run far past it, and CUDD's C code holds
the interpreter lock, so no thread of this process can interrupt it. When a command is
given a limit, the run therefore happens in a forked child process:

- the child sets the address-space limit (``RLIMIT_AS``) to the memory limit and runs the
  solver with CUDD's own limit below it (:func:`cudd_budget_mb`), so CUDD fails cleanly
  first and the solver reports it (:func:`gaitc.solver.synthesis.memory_guard`);
- the parent waits at most the time limit plus :data:`GRACE` seconds, then kills the child;
- a child that dies without an answer (CUDD's C out-of-memory handler calls ``exit(1)``,
  the kernel's OOM killer sends SIGKILL) is reported as running out of memory.

Either way the command ends with a :class:`~gaitc.diagnostics.SolverError` (exit 4, a message and
its JSON record), never with a half-finished file: the child writes nothing, and the
parent writes output files only after the child has answered. The child dies with the
parent, and Ctrl-C kills it before the parent exits with 130
(:mod:`gaitc.diagnostics.processes`).
"""

from __future__ import annotations

import os
import resource
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Final, TypeVar

from gaitc.diagnostics import SolverError
from gaitc.diagnostics.processes import GRACE, can_fork, first_success
from gaitc.solver.game import answer_of
from gaitc.solver.symbolic import Options

T = TypeVar("T")

MIN_ROOM_MB: Final = 32  # the least memory a solver run may have beyond gaitc's own
CUDD_SHARE: Final = 0.75  # of that room, what CUDD's tables may take (the rest: Python)


@dataclass(frozen=True)
class HardLimits:
    """A wall-clock limit in seconds and a memory limit in MB; None for no limit."""

    seconds: float | None = None
    memory_mb: int | None = None

    @property
    def any(self) -> bool:
        return self.seconds is not None or self.memory_mb is not None


def process_mb() -> float:
    """This process's address space in MB (what ``RLIMIT_AS`` counts)."""
    try:
        with open("/proc/self/statm", encoding="ascii") as f:
            pages = int(f.read().split()[0])
        return pages * os.sysconf("SC_PAGE_SIZE") / 2**20
    except (OSError, ValueError, IndexError):
        return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cudd_budget_mb(memory_mb: int) -> int:
    """CUDD's share of a memory limit of ``memory_mb`` for a run started from this process.

    Raises :class:`SolverError` when the limit leaves less than :data:`MIN_ROOM_MB` beyond
    the memory gaitc already takes."""
    own = process_mb()
    room = memory_mb - own
    if room < MIN_ROOM_MB:
        raise SolverError(
            f"a memory limit of {memory_mb} MB is too small: gaitc itself takes "
            f"{own:.0f} MB",
            hint=f"give --memory-limit at least {int(own) + MIN_ROOM_MB + 1} MB")
    return max(1, int(room * CUDD_SHARE))


def solver_options(memory_mb: int | None) -> Options:
    """The embedded solver's options for a memory limit of ``memory_mb`` (None: no limit):
    CUDD's share of it (:func:`cudd_budget_mb`, so a limit too small fails here, before
    any fork)."""
    return Options(memory_mb=None if memory_mb is None else cudd_budget_mb(memory_mb))


def run_limited(work: Callable[[], T], limits: HardLimits, what: str = "synthesis") -> T:
    """``work()``, in a child process bounded by ``limits`` when there are any (and the
    platform can fork); its exceptions are raised here as they were raised there, and a
    time limit passed is ":data:`what` stopped after the time limit"."""
    if not limits.any or not can_fork():
        return work()
    deadline = None if limits.seconds is None else time.monotonic() + limits.seconds + GRACE

    def setup() -> None:
        if limits.memory_mb is not None:
            limit = limits.memory_mb * 2**20
            _, hard = resource.getrlimit(resource.RLIMIT_AS)
            if hard != resource.RLIM_INFINITY:
                limit = min(limit, hard)
            resource.setrlimit(resource.RLIMIT_AS, (limit, hard))

    _, outcome = first_success([work], deadline, setup)
    answer: T = answer_of(outcome, limits.seconds, what)
    return answer
