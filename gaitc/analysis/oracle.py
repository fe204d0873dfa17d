"""The oracle: realizability of spec variants with the embedded solver, counted and timed.

Every answer of :mod:`gaitc.analysis` comes from re-solving; the oracle keeps the number of
solver calls and their time (benchmarks print them) and a deadline for the whole analysis.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from gaitc.diagnostics import SolverError
from gaitc.ir.controller import Controller
from gaitc.ir.spec import GR1Spec, Semantics
from gaitc.solver import synthesis
from gaitc.solver.portfolio import engine_options
from gaitc.solver.symbolic import Options


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
