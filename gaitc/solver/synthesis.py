"""Facade of the embedded solver: realizability, controllers and counter-strategies for a spec.

Each call builds a fresh :class:`~gaitc.solver.symbolic.SymbolicSpec`, solves the game of
:mod:`gaitc.solver.game` and, when asked, extracts an explicit automaton
(:mod:`gaitc.solver.strategy`, :mod:`gaitc.solver.counter`).
"""

from __future__ import annotations

import time
import weakref
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Final

from gaitc.diagnostics import FormulaError
from gaitc.diagnostics.choices import Choice
from gaitc.diagnostics.processes import claim
from gaitc.ir.bits import spec_bits
from gaitc.ir.formula import atoms
from gaitc.ir.spec import SEMANTICS, GR1Spec, Semantics
from gaitc.solver.game import ControllerTooLarge, Game, GameStats, Limits, Progress, out_of_memory
from gaitc.solver.portfolio import STATIC, solve_chosen
from gaitc.solver.preferences import MovePreferences
from gaitc.solver.symbolic import Options, SymbolicSpec

if TYPE_CHECKING:
    from gaitc.ir.bddfile import SymbolicController
    from gaitc.ir.controller import Controller
    from gaitc.ir.costs import Cost

# The extractions (strategy.py, counter.py, symbolic_strategy.py, preferences.py) load in
# the calls that extract: deciding (check) needs only the game.


@dataclass(frozen=True)
class CheckResult:
    """Whether ``spec`` is realizable, how long deciding took, and fixpoint statistics."""

    realizable: bool
    seconds: float
    stats: GameStats = field(default_factory=GameStats)
    engine: str = STATIC  # the configuration that answered (gaitc.solver.portfolio)
    also: Any = None  # what ``check``'s ``also`` made of the game's symbolic spec


def state_bits(spec: GR1Spec) -> int:
    """The number of state bits of ``spec`` (inputs and outputs, integers bit-blasted)."""
    inputs, outputs = spec_bits(spec)
    return len(inputs) + len(outputs)


def _check_semantics(semantics: Semantics) -> None:
    if semantics not in SEMANTICS:
        raise ValueError(f"semantics must be one of {SEMANTICS}, not {semantics!r}")


def _symbolic(spec: GR1Spec, options: Options | None, limits: Limits) -> SymbolicSpec:
    with memory_guard():
        return SymbolicSpec(spec, options, limits.check)


#: What dd.cudd raises when a CUDD operation returns NULL (its memory limit was reached).
_CUDD_FAILURES = ("`DdNode *node` is `NULL` pointer", "CUDD appears to have run out of memory")


@contextmanager
def memory_guard() -> Iterator[None]:
    """Turn running out of memory (Python's MemoryError, or a CUDD operation failing at
    ``Options.memory_mb``) into the solver error the CLI reports with exit 4."""
    try:
        yield
    except MemoryError:
        raise out_of_memory() from None
    except (ValueError, RuntimeError) as err:
        if any(text in str(err) for text in _CUDD_FAILURES):
            raise out_of_memory() from None
        raise


def _game(spec: GR1Spec, semantics: Semantics, options: Options, limits: Limits
          ) -> tuple[SymbolicSpec, Game]:
    """The symbolic game of ``spec``, after the checks the game relies on."""
    _check_semantics(semantics)
    _check_env_trans(spec)
    limits.report("building the transition relation",
                  f"{len(spec.inputs)} inputs, {len(spec.outputs)} outputs, "
                  f"{len(spec.env_trans) + len(spec.sys_trans)} transition clauses")
    sym = _symbolic(spec, options, limits)
    limits.report("building the transition relation", f"{sym.node_count()} live BDD nodes", 1.0)
    # A weak reference: sym already holds limits.check, and a cycle would leave the BDD
    # manager to the garbage collector, which may free it before its nodes.
    check_memory = weakref.WeakMethod(sym.check_memory)

    def memory() -> None:
        method = check_memory()
        if method is not None:
            method()

    limits.memory = memory
    return sym, Game(sym, limits)


def _check_env_trans(spec: GR1Spec) -> None:
    """No next-state output in env_trans, as SLUGS requires (the readers enforce it for
    files; specs built in Python are checked here): the environment moves first."""
    outputs = {v.name for v in spec.outputs}
    for clause in spec.env_trans:
        for name, primed in sorted(atoms(clause.formula)):
            if primed and name in outputs:
                raise FormulaError(
                    f"next-state output '{name}'' cannot appear in env_trans: the environment "
                    "moves before the system and cannot see its next move",
                    clause.origin.span if clause.origin else None,
                )


def check(
    spec: GR1Spec,
    semantics: Semantics = Semantics.DEFAULT,
    timeout: float | None = None,
    progress: Progress | None = None,
    options: Options | None = None,
    *,
    also: Callable[[SymbolicSpec, Callable[[], None]], Any] | None = None,
) -> CheckResult:
    """Decide realizability of ``spec`` under ``semantics`` ("default" or "robotics").

    ``also(sym, check)`` runs once the game is decided, on the game's own
    :class:`SymbolicSpec` (in the process and the time limit of the solve, ``check``
    raising past it), and its answer is the result's ``also``: a second analysis of the
    spec without a second build (the well-separation check of ``gaitc check``)."""
    limits = Limits(timeout, progress)

    def run(chosen: Options, lim: Limits) -> CheckResult:
        sym, game = _game(spec, semantics, chosen, lim)
        with memory_guard():
            result = game.solve(stop_if_lost=semantics)
            ok = game.initially_winning(result.winning, semantics)
            extra = None if also is None else also(sym, lim.check)
        return CheckResult(ok, time.monotonic() - limits.started, result.stats, also=extra)

    _check_semantics(semantics)
    result, engine = solve_chosen(run, options or Options(), limits, state_bits(spec))
    return replace(result, seconds=time.monotonic() - limits.started, engine=engine)


#: The forms a controller can take: ``explicit`` (an automaton, docs/controller-format.md),
#: ``symbolic`` (BDDs, :mod:`gaitc.ir.bddfile`), or ``auto``: explicit unless it would pass
#: ``max_nodes``, then symbolic.
class Extraction(Choice):
    """What the solver leaves of a solved game (the controller forms of
    :class:`gaitc.core.modes.Form` that a solver writes, and the choice between them)."""

    EXPLICIT = "explicit"
    SYMBOLIC = "symbolic"
    AUTO = "auto"


FORMS: Final = Extraction.values()


def synthesize(
    spec: GR1Spec,
    semantics: Semantics = Semantics.DEFAULT,
    timeout: float | None = None,
    progress: Progress | None = None,
    *, options: Options | None = None,
    max_nodes: int | None = None,
    prefer: Sequence[str] = (),
    costs: Sequence[Cost] = (),
) -> Controller | None:
    """An explicit Mealy controller for ``spec``, or None when it is unrealizable.

    ``prefer`` orders the preferences of :mod:`gaitc.solver.preferences` (empty: the first move in
    BDD order); ``costs`` gives the terms of the cost-based ones (e.g. a robot model's).
    """
    from gaitc.ir.bddfile import SymbolicController  # lazy: not on check's path (start-up)

    found = synthesize_controller(
        spec=spec,
        semantics=semantics,
        timeout=timeout,
        progress=progress,
        options=options,
        max_nodes=max_nodes,
        form=Extraction.EXPLICIT,
        prefer=prefer,
        costs=costs,
    )
    assert not isinstance(found, SymbolicController)
    return found


def synthesize_controller(
    spec: GR1Spec,
    semantics: Semantics = Semantics.DEFAULT,
    timeout: float | None = None,
    progress: Progress | None = None,
    *, options: Options | None = None,
    max_nodes: int | None = None,
    form: Extraction | str = Extraction.AUTO,
    prefer: Sequence[str] = (),
    costs: Sequence[Cost] = (),
) -> Controller | SymbolicController | None:
    """A controller for ``spec`` in ``form`` (:data:`FORMS`), or None when unrealizable;
    either form chooses its moves by ``prefer`` and ``costs`` (see :func:`synthesize`)."""
    # lazy: here, not in run: run may be a forked racer's, and a forked process imports
    # nothing; and not at the top, since they are not on check's path (start-up)
    from gaitc.solver.strategy import extract_strategy
    from gaitc.solver.symbolic_strategy import symbolic_controller

    if form not in FORMS:
        raise ValueError(f"form must be one of {FORMS}, not {form!r}")
    form = Extraction(form)

    def run(chosen: Options, lim: Limits) -> Controller | SymbolicController | None:
        sym, game = _game(spec, semantics, chosen, lim)
        with memory_guard():
            result = game.solve(keep_layers=True)
            claim()  # in a race, this racer extracts the controller alone
            if not game.initially_winning(result.winning, semantics):
                return None
            moves = MovePreferences(sym, result, costs, prefer, lim) if prefer else None
            if form != Extraction.SYMBOLIC:
                lim.report("extracting the controller")
                try:
                    return extract_strategy(sym, result, semantics, lim, max_nodes, moves)
                except ControllerTooLarge:
                    if form == Extraction.EXPLICIT:
                        raise
                    lim.report("keeping the controller symbolic", f"over {max_nodes} nodes")
            lim.report("writing the strategy as BDDs")
            return symbolic_controller(sym, result, semantics, moves, lim)

    _check_semantics(semantics)
    return solve_chosen(run, options or Options(), Limits(timeout, progress),
                        state_bits(spec))[0]


def counterstrategy(
    spec: GR1Spec,
    semantics: Semantics = Semantics.DEFAULT,
    timeout: float | None = None,
    progress: Progress | None = None,
    options: Options | None = None,
    max_nodes: int | None = None,
) -> Controller | None:
    """The environment's winning strategy for an unrealizable ``spec``; None if realizable."""
    # lazy: before run forks, as above, and not on check's path (start-up)
    from gaitc.solver.counter import extract_counterstrategy

    def run(chosen: Options, lim: Limits) -> Controller | None:
        sym, game = _game(spec, semantics, chosen, lim)
        with memory_guard():
            result = game.solve()
            claim()  # in a race, this racer extracts the counter-strategy alone
            if game.initially_winning(result.winning, semantics):
                return None
            lim.report("extracting the counter-strategy")
            return extract_counterstrategy(sym, result.winning, semantics, lim, max_nodes)

    _check_semantics(semantics)
    return solve_chosen(run, options or Options(), Limits(timeout, progress),
                        state_bits(spec))[0]
