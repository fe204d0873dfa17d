"""Facade of the embedded solver: realizability, controllers and counter-strategies for a spec.

Each call builds a fresh :class:`~slugs_bridge.symbolic.SymbolicSpec`, solves the game of
:mod:`slugs_bridge.game` and, when asked, extracts an explicit automaton
(:mod:`slugs_bridge.strategy`, :mod:`slugs_bridge.counter`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

from slugs_bridge.controller import Controller
from slugs_bridge.counter import extract_counterstrategy
from slugs_bridge.diagnostics import SolverError
from slugs_bridge.game import SEMANTICS, Game, GameStats, Limits, Progress
from slugs_bridge.spec import GR1Spec
from slugs_bridge.strategy import extract_strategy
from slugs_bridge.symbolic import Options, SymbolicSpec


@dataclass(frozen=True)
class CheckResult:
    """Whether ``spec`` is realizable, how long deciding took, and fixpoint statistics."""

    realizable: bool
    seconds: float
    stats: GameStats = field(default_factory=GameStats)


def _check_semantics(semantics: str) -> None:
    if semantics not in SEMANTICS:
        raise ValueError(f"semantics must be one of {SEMANTICS}, not {semantics!r}")


def _symbolic(spec: GR1Spec, options: Options | None, limits: Limits) -> SymbolicSpec:
    try:
        return SymbolicSpec(spec, options, limits.check)
    except MemoryError:
        raise _out_of_memory() from None


def _out_of_memory() -> SolverError:
    return SolverError(
        "synthesis ran out of memory",
        hint="raise --memory-limit, or shrink the specification (grid, health levels, encoding)",
    )


def check(
    spec: GR1Spec,
    semantics: str = "default",
    timeout: float | None = None,
    progress: Progress | None = None,
    options: Options | None = None,
) -> CheckResult:
    """Decide realizability of ``spec`` under ``semantics`` ("default" or "robotics")."""
    _check_semantics(semantics)
    started = time.monotonic()
    limits = Limits(timeout, progress, started)
    sym = _symbolic(spec, options, limits)
    game = Game(sym, limits)
    try:
        result = game.solve(stop_if_lost=semantics)
        ok = game.initially_winning(result.winning, semantics)
    except MemoryError:
        raise _out_of_memory() from None
    return CheckResult(ok, time.monotonic() - started, result.stats)


def synthesize(
    spec: GR1Spec,
    semantics: str = "default",
    timeout: float | None = None,
    progress: Progress | None = None,
    options: Options | None = None,
    max_nodes: int | None = None,
) -> Controller | None:
    """An explicit Mealy controller for ``spec``, or None when it is unrealizable."""
    _check_semantics(semantics)
    limits = Limits(timeout, progress)
    sym = _symbolic(spec, options, limits)
    game = Game(sym, limits)
    try:
        result = game.solve(keep_layers=True)
        if not game.initially_winning(result.winning, semantics):
            return None
        limits.report("extracting the explicit controller")
        return extract_strategy(sym, result, semantics, limits, max_nodes)
    except MemoryError:
        raise _out_of_memory() from None


def counterstrategy(
    spec: GR1Spec,
    semantics: str = "default",
    timeout: float | None = None,
    progress: Progress | None = None,
    options: Options | None = None,
    max_nodes: int | None = None,
) -> Controller | None:
    """The environment's winning strategy for an unrealizable ``spec``; None if realizable."""
    _check_semantics(semantics)
    limits = Limits(timeout, progress)
    sym = _symbolic(spec, options, limits)
    game = Game(sym, limits)
    try:
        result = game.solve()
        if game.initially_winning(result.winning, semantics):
            return None
        limits.report("extracting the counter-strategy")
        return extract_counterstrategy(sym, result.winning, semantics, limits, max_nodes)
    except MemoryError:
        raise _out_of_memory() from None
