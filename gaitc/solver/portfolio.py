"""The engine chooses its configuration per problem: a race of two variable orders (issue 12).

The solver's defaults (the guards-first static order, CUDD's dynamic reordering off) were
tuned on the thesis family, where sifting costs 2-8x (docs/design-notes.md, section 4); on
other families, such as the AMBA AHB arbiters, building the transition relation in that
order blows up (AMBA with 4 masters: 160 s to build what takes 0.1 s in a sifted order).
No cheap test tells the two apart before solving, so two forked processes race:

1. the static guards order builds and solves the spec; most specs are decided within
   :data:`HEAD_START` seconds, at the cost of one fork (a few milliseconds);
2. then a second process joins, niced: the same guards order, but CUDD sifts variable
   groups (each bit with its primed copy) whenever the relation grows while it is built,
   once more when it is built, and then keeps that order fixed for the fixpoint (the
   first racer, whose build may have started again sifting too, sifts throughout its
   fixpoint after :data:`~gaitc.solver.options.RACE_SIFT_AFTER` seconds, so the two differ). The
   first answer wins and the other process is killed; a synthesis is won by the racer
   that solves the game first (it claims the answer, :func:`gaitc.diagnostics.processes.claim`),
   which then extracts the controller alone, so a long extraction does not run twice,
   in twice the memory. The machines gaitc targets have two cores, so each racer runs at
   full speed.

Sifting while building and then solving in a fixed order beat sifting throughout: on
AMBA the fixpoint then takes 1.1 s at 5 masters and 11 s at 8 (dynamic sifting
throughout: 1.6 s and over 120 s), and on the thesis grid 10 x 10 at health 4 (binary)
5.9 s against 16 s for the static order.

The static solve runs in a child, not in this process, because one CUDD operation can
take minutes and holds the interpreter lock: on AMBA with 5 masters, simplifying the
transition relation in the guards order is one such call, so a head start in this
process could not be cut off.

This is the portfolio idea of Firman, Maoz and Ringert, "Performance heuristics for GR(1)
synthesis and related algorithms" (Acta Informatica 57, 2020), reduced to the switch
that paid here. An explicit ``Options(reordering=True/False)``, a memory budget (two
racers would need twice the memory), a platform without ``fork``, or a spec of at most
:data:`SMALL_BITS` state bits skips the race; such a small spec is solved in this process,
in the static order until a step shows that order misfits, and then built again in the
sifted order (:class:`~gaitc.solver.game.OrderMisfit`).
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import replace
from typing import Final, TypeVar

from gaitc.diagnostics import GaitcError, SolverError
from gaitc.diagnostics.processes import GRACE, can_fork, first_success, to_parent
from gaitc.solver.game import Limits, OrderMisfit, out_of_memory, time_limit_error
from gaitc.solver.options import RACE_SIFT_AFTER, SMALL_BITS
from gaitc.solver.symbolic import Options

T = TypeVar("T")
__all__ = ["DYNAMIC", "HEAD_START", "SIFTED", "SMALL_BITS", "STATIC", "engine_options",
           "solve_chosen"]

#: Seconds the static configuration runs alone.  Rows that the sifted order solves in half
#: a second pay the head start in full (thesis 10 x 10 health 3 binary: 0.77 s raced after
#: 0.25 s, 0.57 s after 0.1 s, 0.53 s for its best configuration alone).
HEAD_START: Final = 0.1
#: The second racer runs at a lower priority: on an idle two-core machine it still gets its
#: own core, and on a busy one it does not slow the first down (thesis robot A on a loaded
#: machine: 1.64 s raced at equal priority against 1.02 s for the static order alone).
SECOND_NICENESS: Final = 10
STATIC: Final = "static order"
SIFTED: Final = "sifted order"
DYNAMIC: Final = "dynamic reordering"  # only when asked for: Options(reordering=True)


def engine_options(engine: str, base: Options | None = None) -> Options:
    """The options of the racer named ``engine`` (to solve variants of a spec without a
    race once the race on the spec itself has chosen)."""
    base = base or Options()
    if engine == SIFTED:
        return replace(base, reordering=False, sift_build=True)
    if engine == DYNAMIC:
        return replace(base, reordering=True)
    return replace(base, reordering=False)


def solve_chosen(run: Callable[[Options, Limits], T], options: Options, limits: Limits,
                 bits: int | None = None) -> tuple[T, str]:
    """``run(options, limits)`` in the configuration the engine chooses, and its name;
    ``bits`` is the spec's number of state bits, when the caller knows it."""
    if options.reordering is not None or options.memory_mb is not None or not can_fork():
        return run(options, limits), DYNAMIC if options.reordering else STATIC
    if bits is not None and bits <= SMALL_BITS:
        try:
            return run(replace(engine_options(STATIC, options), restart_misfit=True),
                       limits), STATIC
        except OrderMisfit:  # a step showed the guards order misfits: build it sifted
            return run(engine_options(SIFTED, options), limits), SIFTED
    # Progress comes back through the pipes: the static racer's, and once a racer has
    # claimed the answer (gaitc.solver.synthesis: it solved the game first), that racer's.
    reporting = replace(limits, progress=None if limits.progress is None else to_parent)
    # The racers differ in the game too: a restarted static build is sifted like the
    # second racer's, so its game sifts throughout after a while and the other stays fixed.
    static = replace(engine_options(STATIC, options), sift_after=RACE_SIFT_AFTER)
    sifted = engine_options(SIFTED, options)

    def second() -> T:
        os.nice(SECOND_NICENESS)  # in its own process: yields the CPU it would steal
        return run(sifted, reporting)

    works = [lambda: run(static, reporting), second]
    deadline = None if limits.timeout is None else limits.started + limits.timeout + GRACE
    index, outcome = first_success(works, deadline, delays=(0.0, HEAD_START),
                                   relay=limits.progress)
    names = (STATIC, SIFTED)
    if outcome[0] == "ok":
        answer: T = outcome[1]
        return answer, names[index]
    if outcome[0] == "raise":
        err = outcome[1]
        if isinstance(err, MemoryError):
            raise out_of_memory()
        if not isinstance(err, GaitcError) and os.environ.get("GAITC_DEBUG"):
            print(outcome[2], file=sys.stderr, end="")
        raise err
    if outcome[0] == "timeout":
        raise time_limit_error(limits.timeout or 0.0)
    raise SolverError(f"both solver processes ended without an answer (exit status "
                      f"{outcome[1]}); the machine may be out of memory")
