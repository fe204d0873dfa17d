"""The engine chooses its configuration per problem: a head start, then a race (issue 12).

The solver's defaults (the guards-first static order, CUDD's dynamic reordering off) were
tuned on the thesis family, where sifting costs 2-8x (docs/performance.md, section 4); on
other families, such as the AMBA AHB arbiters, the static order blows up and dynamic
reordering is 100x faster. No cheap test tells the two apart before solving, so:

1. the static configuration runs in this process for :data:`HEAD_START` seconds; most
   specs are decided within it, at no cost;
2. a spec still undecided then is raced: two forked processes solve it from scratch, one
   with the static order and one with dynamic reordering (group sifting, each bit kept
   with its primed copy), and the first answer wins; the other process is killed. The
   machines gaitc targets have two cores, so each racer runs at full speed.

This is the portfolio idea of Firman, Maoz and Ringert, "Performance heuristics for GR(1)
synthesis and related algorithms" (Acta Informatica 57, 2020), reduced to the one switch
that paid here. An explicit ``Options(reordering=True/False)``, a memory budget (two
racers would need twice the memory), or a platform without ``fork`` skips the race.
"""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Final, TypeVar

from diagnostics import GaitcError, SolverError
from diagnostics.processes import can_fork, first_success
from solver.game import HandOff, Limits
from solver.symbolic import Options

T = TypeVar("T")

HEAD_START: Final = 1.0  # seconds the static configuration runs alone, in this process
GRACE: Final = 0.5  # seconds past the time limit before a racer is killed
STATIC: Final = "static order"
DYNAMIC: Final = "dynamic reordering"


def solve_chosen(run: Callable[[Options, Limits], T], options: Options, limits: Limits
                 ) -> tuple[T, str]:
    """``run(options, limits)`` in the configuration the engine chooses, and its name."""
    if options.reordering is not None or options.memory_mb is not None or not can_fork():
        return run(options, limits), DYNAMIC if options.reordering else STATIC
    head = replace(limits, handoff=time.monotonic() + HEAD_START)
    try:
        return run(replace(options, reordering=False), head), STATIC
    except HandOff:
        pass
    limits.report(f"racing the {STATIC} against {DYNAMIC} in two processes")
    quiet = replace(limits, progress=None, memory=None, handoff=None)
    names = (STATIC, DYNAMIC)
    works = [lambda: run(replace(options, reordering=False), replace(quiet)),
             lambda: run(replace(options, reordering=True), replace(quiet))]
    deadline = None if limits.timeout is None else limits.started + limits.timeout + GRACE
    index, outcome = first_success(works, deadline)
    if outcome[0] == "ok":
        answer: T = outcome[1]
        return answer, names[index]
    if outcome[0] == "raise":
        err = outcome[1]
        if isinstance(err, MemoryError):
            raise SolverError("synthesis ran out of memory")
        if not isinstance(err, GaitcError) and os.environ.get("GAITC_DEBUG"):
            print(outcome[2], file=sys.stderr, end="")
        raise err
    if outcome[0] == "timeout":
        raise SolverError(f"synthesis stopped after the time limit of {limits.timeout:g} s",
                          hint="raise --timeout, or simplify the specification")
    raise SolverError(f"both solver processes ended without an answer (exit status "
                      f"{outcome[1]}); the machine may be out of memory")
