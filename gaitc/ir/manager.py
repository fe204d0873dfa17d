"""A fresh ``dd.cudd`` BDD manager, sized for the games gaitc solves.

Every BDD manager of the project (the solver's, the independent verifier's, a symbolic
controller's runtime) starts here, so that all of them start small.  CUDD allocates its
computed table at the size asked for and clears every slot at once; dd asks for 262,144
slots by default, and that initialization took 5-7 ms of every `gaitc check` of a small
spec, whose whole solve takes 2-3 ms (a lift with two floors: 9.6 ms against 2.9 ms; the
random corpus alike).  CUDD doubles the table by itself while its hit rate is high (Somenzi,
CUDD 3.0 user's manual, "The computed table"), so larger games lose nothing: thesis robot A
and the 10 x 10 health 3 grid, AMBA with 5 and 8 masters and the 64-client arbiter solve in
the same time within noise (docs/design-notes.md, section 9).
"""

from __future__ import annotations

from typing import Final

from gaitc.ir.cuddlib import cudd

#: The computed table's initial slots (dd's default: 262,144).
INITIAL_CACHE_SLOTS: Final = 1 << 16


def manager(memory_bytes: int | None = None) -> cudd.BDD:
    """A new manager with its dynamic reordering off; ``memory_bytes`` is both CUDD's memory
    estimate and its hard limit (a MemoryError past it), None for dd's defaults."""
    if memory_bytes is None:
        bdd = cudd.BDD(initial_cache_size=INITIAL_CACHE_SLOTS)
    else:
        bdd = cudd.BDD(memory_estimate=memory_bytes, initial_cache_size=INITIAL_CACHE_SLOTS)
        bdd.configure(max_memory=memory_bytes)
    bdd.configure(reordering=False)
    return bdd
