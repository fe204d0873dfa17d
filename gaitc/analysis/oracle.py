"""The oracle: realizability of spec variants with the embedded solver, counted and timed.

Every answer of :mod:`gaitc.analysis` comes from re-solving; the oracle keeps the number of
solver calls and their time (benchmarks print them) and a deadline for the whole analysis.
"""

from __future__ import annotations

import multiprocessing
import os
import time
from dataclasses import dataclass, field
from multiprocessing.connection import Connection
from typing import Any, Final

from gaitc.diagnostics import SolverError
from gaitc.diagnostics.processes import as_worker, can_fork, signals_held
from gaitc.ir.controller import Controller
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver import synthesis
from gaitc.solver.portfolio import engine_options
from gaitc.solver.symbolic import Options

#: The processes that solve a batch of variants at once (the cores, at most four).
WORKERS: Final = max(1, min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                             else (os.cpu_count() or 1)))


def _worker(share: list[GR1Spec], semantics: Semantics, options: Options,
            timeout: float | None, out: Connection) -> None:
    """A worker process: decide its share of the variants (it has them from the fork, so
    nothing is pickled on the way in) and send the answers, or the solver's error, back.
    Ctrl-C is the parent's to handle; SIGTERM (the parent stopping it) ends it quietly."""
    as_worker()
    try:
        out.send([synthesis.check(spec, semantics, timeout, options=options).realizable
                  for spec in share])
    except SolverError as err:
        out.send(err)
    finally:
        out.close()


def _solve_shares(shares: list[list[GR1Spec]], semantics: Semantics, options: Options,
                  timeout: float | None) -> list[list[bool]]:
    """Each share decided in its own forked process; every worker is stopped and reaped
    whatever happens here (an error, Ctrl-C, SIGTERM)."""
    context = multiprocessing.get_context("fork")
    running: list[tuple[Any, Connection]] = []
    try:
        for share in shares:
            receiver, sender = context.Pipe(duplex=False)
            with signals_held():  # a Ctrl-C during the fork waits until it is done
                child = context.Process(target=_worker, args=(share, semantics, options,
                                                              timeout, sender), daemon=True)
                child.start()
            sender.close()
            running.append((child, receiver))
        out: list[list[bool]] = []
        for child, receiver in running:
            try:
                got = receiver.recv()
            except EOFError:
                raise SolverError(f"a solver process ended without an answer (exit code "
                                  f"{child.exitcode}), perhaps out of memory") from None
            if isinstance(got, SolverError):
                raise got
            out.append(got)
        return out
    finally:
        for child, receiver in running:
            if child.is_alive():
                child.terminate()
            child.join()
            receiver.close()


@dataclass
class Oracle:
    """Solves variants under one semantics until ``deadline`` (a ``time.monotonic`` value)."""

    semantics: Semantics = Semantics.DEFAULT
    deadline: float | None = None
    calls: int = 0
    seconds: float = 0.0
    _memo: dict[GR1Spec, bool] = field(default_factory=dict, repr=False)
    # The configuration that won the first call's race (gaitc.solver.portfolio): the variants
    # are the same problem, so they reuse it without racing (no fork per call).
    _options: Options | None = field(default=None, repr=False)

    @classmethod
    def within(cls, semantics: Semantics, timeout: float | None) -> Oracle:
        deadline = None if timeout is None else time.monotonic() + timeout
        return cls(semantics, deadline)

    def _left(self) -> float | None:
        if self.deadline is None:
            return None
        left = self.deadline - time.monotonic()
        if left <= 0:
            raise SolverError(f"the analysis ran out of time after {self.calls} solver calls",
                              hint="raise --timeout, or skip the repairs (--no-repairs)")
        return left

    def _timed_out(self, err: SolverError) -> SolverError:
        """The analysis's own deadline, rather than the last call's share of it."""
        if self.deadline is not None and time.monotonic() >= self.deadline - 0.5:
            return SolverError(f"the analysis ran out of time after {self.calls} solver calls",
                               hint="raise --timeout, or skip the repairs (--no-repairs)")
        return err

    def realizable(self, spec: GR1Spec) -> bool:
        """Whether ``spec`` is realizable (answers for equal specs are remembered)."""
        known = self._memo.get(spec)
        if known is not None:
            return known
        started = time.monotonic()
        self.calls += 1
        try:
            result = synthesis.check(spec, self.semantics, self._left(), options=self._options)
            if self._options is None:
                self._options = engine_options(result.engine)
            answer = result.realizable
        except SolverError as err:
            raise self._timed_out(err) from None
        finally:
            self.seconds += time.monotonic() - started
        self._memo[spec] = answer
        return answer

    def realizable_all(self, specs: list[GR1Spec]) -> list[bool]:
        """Whether each of ``specs`` is realizable, in order: remembered answers first, the
        rest solved at once on :data:`WORKERS` processes (one when there is only one to
        solve, or one core), each with the configuration the first call's race chose."""
        unknown = list(dict.fromkeys(s for s in specs if s not in self._memo))
        workers = min(WORKERS, len(unknown))
        if workers <= 1 or self._options is None or not can_fork():
            return [self.realizable(s) for s in specs]
        started = time.monotonic()
        self.calls += len(unknown)
        left = self._left()
        shares = [unknown[k::workers] for k in range(workers)]
        try:
            answers_of = _solve_shares(shares, self.semantics, self._options, left)
        except SolverError as err:
            raise self._timed_out(err) from None
        finally:
            self.seconds += time.monotonic() - started
        for share, answers in zip(shares, answers_of, strict=True):
            self._memo.update(zip(share, answers, strict=True))
        return [self._memo[s] for s in specs]

    def counterstrategy(self, spec: GR1Spec) -> Controller | None:
        """The environment's winning strategy, or None when ``spec`` is realizable."""
        started = time.monotonic()
        self.calls += 1
        try:
            return synthesis.counterstrategy(spec, self.semantics, self._left(),
                                             options=self._options)
        except SolverError as err:
            raise self._timed_out(err) from None
        finally:
            self.seconds += time.monotonic() - started
