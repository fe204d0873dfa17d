"""The engine chooses its configuration per problem: a head start, then a race (issue 12).

The solver's defaults (the guards-first static order, CUDD's dynamic reordering off) were
tuned on the thesis family, where sifting costs 2-8x (docs/performance.md, section 4); on
other families, such as the AMBA AHB arbiters, the static order blows up and dynamic
reordering is 100x faster. No cheap test tells the two apart before solving, so:

1. the static guards order solves the spec in a forked process; most specs are decided
   within :data:`HEAD_START` seconds, at the cost of one fork (a few milliseconds);
2. if not, a second process joins the race with dynamic reordering (group sifting, each
   bit kept with its primed copy) started from the occurrence order, without the invariant
   care set; the first answer wins and the other process is killed. The machines gaitc
   targets have two cores, so each racer runs at full speed.

The static solve runs in a child, not in this process, because one CUDD operation can
take minutes and holds the interpreter lock: on AMBA with 5 masters, simplifying the
transition relation in the guards order is one such call, so a head start in this
process could not be cut off.

The second racer drops the care set: on AMBA the restricted relations sift worse (CPU
seconds with and without it: 0.85 / 0.27 at 3 masters, 2.8 / 1.7 at 5). Its start
matters too: on AMBA with 3 masters, sifting from the guards order
takes 3.4 s, from the declaration order 0.7 s, and from the occurrence order 0.7 s. With
4 masters those are 5.2 s from the declaration order and 1.1 s from the occurrence order.

This is the portfolio idea of Firman, Maoz and Ringert, "Performance heuristics for GR(1)
synthesis and related algorithms" (Acta Informatica 57, 2020), reduced to the one switch
that paid here. An explicit ``Options(reordering=True/False)``, a memory budget (two
racers would need twice the memory), or a platform without ``fork`` skips the race.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from dataclasses import replace
from typing import Final, TypeVar

from diagnostics import GaitcError, SolverError
from diagnostics.processes import GRACE, can_fork, first_success, to_parent
from solver.game import Limits, out_of_memory, time_limit_error
from solver.symbolic import Options

T = TypeVar("T")

HEAD_START: Final = 0.25  # seconds the static configuration runs alone
#: The second racer runs at a lower priority: on an idle two-core machine it still gets its
#: own core, and on a busy one it does not slow the first down (thesis robot A on a loaded
#: machine: 1.64 s raced at equal priority against 1.02 s for the static order alone).
SECOND_NICENESS: Final = 10
STATIC: Final = "static order"
DYNAMIC: Final = "dynamic reordering"


def engine_options(engine: str, base: Options | None = None) -> Options:
    """The options of the racer named ``engine`` (to solve variants of a spec without a
    race once the race on the spec itself has chosen)."""
    base = base or Options()
    if engine == DYNAMIC:
        return replace(base, reordering=True, order="occurrence", care=False)
    return replace(base, reordering=False)


def solve_chosen(run: Callable[[Options, Limits], T], options: Options, limits: Limits
                 ) -> tuple[T, str]:
    """``run(options, limits)`` in the configuration the engine chooses, and its name."""
    if options.reordering is not None or options.memory_mb is not None or not can_fork():
        return run(options, limits), DYNAMIC if options.reordering else STATIC
    # The static racer's progress comes back through the pipe; the other racer is quiet.
    reporting = replace(limits, progress=None if limits.progress is None else to_parent)
    quiet = replace(limits, progress=None)
    static, dynamic = engine_options(STATIC, options), engine_options(DYNAMIC, options)
    def second() -> T:
        os.nice(SECOND_NICENESS)  # in its own process: yields the CPU it would steal
        return run(dynamic, quiet)

    works = [lambda: run(static, reporting), second]
    deadline = None if limits.timeout is None else limits.started + limits.timeout + GRACE
    index, outcome = first_success(works, deadline, delays=(0.0, HEAD_START),
                                   relay=limits.progress)
    names = (STATIC, DYNAMIC)
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
