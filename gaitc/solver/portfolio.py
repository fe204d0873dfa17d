"""The engine's plan per problem: one process, one order at a time, every switch by a count.

The solver's defaults (the guards-first static order, CUDD's dynamic reordering off) were
tuned on the thesis family, where sifting costs 2-8x (docs/design-notes.md, section 4); on
other families they misfit, and the engine switches, always on a count of nodes or of
CUDD's operations and never on the time a step took, so that a spec takes the same path,
and about the same time, on every run and on a loaded machine:

1. the build starts in the static order and starts again with CUDD sifting when a
   partial transition relation passes :data:`~gaitc.solver.options.SIFT_TRIGGER` nodes a
   bit (the AMBA arbiters), or is sifted once built when ρs comes out far larger than its
   clauses (:data:`~gaitc.solver.options.SIFT_BLOWUP`; AMBA in the bit encoding);
2. the game then sifts in place when a step's image blows up
   (:data:`~gaitc.solver.options.RESIFT_BLOWUP`; the moving-obstacle games) or, after a
   refitted build, when its steps do too much work
   (:data:`~gaitc.solver.options.RESIFT_WORK`);
3. a game whose steps work far harder than its sets are large
   (:data:`~gaitc.solver.options.MISFIT_RATIO`; SLUGS's EvasionOnGrid example) stops and is
   built again with CUDD's sifting throughout, the configuration of the peers, gr1c and
   SLUGS; a small game (at most :data:`~gaitc.solver.options.SMALL_BITS` state bits) whose
   steps are slow is built again in the sifted order
   (:class:`~gaitc.solver.game.OrderMisfit`).

Until issue 50 two forked processes raced here, the static order against a sifted one,
the first answer winning. The race cost a second core's CPU and twice the memory for a
gain of at most 25 % on the families measured (AMBA in the bit encoding with 3 and 4
masters), and it made the time of one spec vary up to 8x between runs (a 1024 x 1024
gridworld: 19.8 s to 160 s), since which racer won, and when each switched to sifting,
depended on the machine's load. A run under ``--timeout`` or ``--memory-limit`` still runs
in a child process that can be killed (:mod:`gaitc.api.isolation`).

References: the portfolio idea of Firman, Maoz and Ringert, "Performance heuristics for
GR(1) synthesis and related algorithms" (Acta Informatica 57, 2020), reduced to switches
that are decided by counts.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Final, TypeVar

from gaitc.diagnostics.processes import GRACE, can_fork, first_success, to_parent
from gaitc.solver.game import Limits, OrderMisfit, answer_of
from gaitc.solver.options import SMALL_BITS
from gaitc.solver.symbolic import Options

T = TypeVar("T")
__all__ = ["DYNAMIC", "SIFTED", "SMALL_BITS", "STATIC", "engine_options", "solve_chosen"]

STATIC: Final = "static order"
SIFTED: Final = "sifted order"
DYNAMIC: Final = "dynamic reordering"


def engine_options(engine: str, base: Options | None = None) -> Options:
    """The options of the configuration named ``engine`` (to solve variants of a spec in
    the configuration the plan chose for the spec itself)."""
    base = base or Options()
    if engine == SIFTED:
        return replace(base, reordering=False, sift_build=True)
    if engine == DYNAMIC:
        return replace(base, reordering=True)
    return replace(base, reordering=False)


def solve_chosen(run: Callable[[Options, Limits], T], options: Options, limits: Limits,
                 bits: int | None = None) -> tuple[T, str]:
    """``run(options, limits)`` in the configuration the plan chooses, and its name;
    ``bits`` is the spec's number of state bits, when the caller knows it.

    Options that fix the configuration (``reordering`` set, a memory budget) are run as
    given. Otherwise the static configuration runs first and, when its game shows that
    its order misfits (:class:`~gaitc.solver.game.OrderMisfit`), the spec is built again
    in the configuration the misfit names.

    With a time limit the plan runs in one forked child, killed :data:`GRACE` seconds
    past the limit: one CUDD operation can take minutes and holds the interpreter lock,
    so the deadline checks between fixpoint steps could not stop it here."""
    if limits.timeout is None or not can_fork():
        return _plan(run, options, limits, bits)
    reporting = replace(limits, progress=None if limits.progress is None else to_parent)
    deadline = limits.started + limits.timeout + GRACE
    _, outcome = first_success([lambda: _plan(run, options, reporting, bits)], deadline,
                               relay=limits.progress)
    answer: tuple[T, str] = answer_of(outcome, limits.timeout)
    return answer


def _plan(run: Callable[[Options, Limits], T], options: Options, limits: Limits,
          bits: int | None) -> tuple[T, str]:
    if options.reordering is not None or options.memory_mb is not None:
        return run(options, limits), DYNAMIC if options.reordering else STATIC
    small = bits is not None and bits <= SMALL_BITS
    try:
        return run(replace(engine_options(STATIC, options), restart_misfit=small,
                           refit_sift=True, rebuild_misfit=True), limits), STATIC
    except OrderMisfit as misfit:
        engine = DYNAMIC if misfit.dynamic else SIFTED
        limits.report("building the transition relation again",
                      "sifting throughout" if misfit.dynamic else "in a sifted order")
        return run(engine_options(engine, options), limits), engine
