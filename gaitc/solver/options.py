"""The embedded solver's tuning switches and the thresholds they use.

Each switch is measured in docs/design-notes.md; :mod:`gaitc.solver.portfolio` chooses between
them per problem, so a normal run sets none of them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Final

#: ``Options.sift_above``: a partial transition relation with more BDD nodes than this per
#: state bit means the static order does not fit the spec.  Measured: the thesis family
#: stays under 130 nodes a bit (30 x 30 one-hot grid: 118,040 nodes, 939 bits), the AMBA
#: arbiters pass 1,600 with 2 masters and 8,600 with 3, and building them in the static
#: order then takes minutes (4 masters: 160 s, against 0.1 s once CUDD sifts).
SIFT_TRIGGER: Final = 400

#: ``Options.sift_blowup``: a static build that did not restart, but whose finished ρs has
#: more than this many times the nodes of its clauses' BDDs together, is sifted once, to
#: convergence, before the fixpoint (``SymbolicSpec.settled``): an order that fits ρs
#: builds it in about the nodes of its parts or fewer.  Measured in the static order: the
#: thesis grids 0.05-0.6, hazard grids 0.15-0.8, the SYNTCOMP safety games 2-3.1, the SLUGS
#: examples at most 5.1 (fastslow_ICRA), the random corpus 2.3, and the bit encoding of
#: AMBA with two masters 20 (6,819 nodes from clauses of 335; 2.5 s to solve fixed, 0.25 s
#: sifted once).
SIFT_BLOWUP: Final = 10

#: After such a restart the fixpoint runs in the sifted order, fixed, until one of its CPre
#: steps takes this many seconds; then CUDD's sifting is turned on for the rest of the game
#: (``Game.resume_sifting``; the step time is measured anyway, while counting live nodes
#: scans CUDD's unique table).  Measured on the AMBA arbiters, solve only: a fixed order
#: wins up to 6 masters (slowest step 0.035 s; 0.7 s against 1.8 s sifting throughout),
#: sifting from 8 masters on (slowest steps 0.1-1.3 s; 9 masters: 92 s fixed, 20-30 s).
RESIFT_STEP: Final = 0.05

#: In the race (gaitc.solver.portfolio) the second racer builds in a sifted order too, so a
#: restarted static build would run the same fixed-order game twice.  The static racer's
#: game (``Options.sift_after``) therefore sifts throughout once a refitted build's fixpoint
#: has run this many seconds, and the second racer keeps its order fixed.  Measured, the
#: static racer alone, solve seconds fixed against switching at 0.3 s: GenBuf 24 senders 6.4
#: against 3.3, 16 senders 1.2 against 1.3; AMBA (bit encoding) 3 masters 1.15 against 0.96,
#: 5 masters 3.3 against 3.3; AMBA (integer) 6 masters 0.94 against 1.19, 8 masters 3.0
#: against 2.5.  Where the fixed order wins, the second racer answers with it.
RACE_SIFT_AFTER: Final = 0.3

#: Specs of at most this many state bits are solved in this process in the static order,
#: without a race (gaitc.solver.portfolio): no set of states over 20 bits has more than 2^20 BDD
#: nodes and the build restarts before a partial relation passes 8,000 (SIFT_TRIGGER a
#: bit), while a fork costs about 0.01 s against solves of 0.01-0.03 s (the SLUGS examples,
#: the random corpus: twice their time raced).  A step of such a game slower than
#: SMALL_STEP seconds shows that its order misfits, and sifting 40 variables is cheap: the
#: moving obstacle 8 x 8 (18 bits) has steps of 0.02-0.07 s in the guards order, 1.0 s to
#: solve fixed and 0.2 s sifting; the SLUGS examples and random-corpus specs this small
#: take at most 0.004 s a step (thesis robots A and B have 27 bits and more).
SMALL_BITS: Final = 20
SMALL_STEP: Final = 0.01
#: A small game whose misfit step finds more live nodes than this is built again in the
#: sifted order rather than sifted in place (gaitc.solver.game.OrderMisfit): a random 18-bit
#: spec of two counters held a million nodes then, and its first sifting took 15 s.
RESTART_NODES: Final = 250_000

#: Any other fixed order sifts again after a step whose ∃y' image (the system's half of
#: CPre) has more than RESIFT_NODES nodes and RESIFT_BLOWUP times the nodes of the step's
#: target and result together.  Measured, static order, the largest ratio of a run: the
#: thesis grids 0.1, hazard grids 0.6, AMBA 3.1 (restarted anyway), the moving-obstacle
#: games 4.2 at their second step and 13 later (16 x 16 with 4 glitches: over 200 s in the
#: fixed order, 0.7 s sifting throughout).  Below the node floor a step takes milliseconds.
RESIFT_BLOWUP: Final = 4
RESIFT_NODES: Final = 10_000


@dataclass
class Options:
    """Tuning switches of the symbolic solver (each measured in docs/design-notes.md)."""

    order: str = "guards"  # see solver.ordering.ORDERS
    care: bool = True  # solve modulo the invariants of ρe/ρs (see SymbolicSpec.care)
    reordering: bool | None = None  # CUDD's group sifting throughout; None: solver.portfolio
    reorder_once: bool = False  # one sifting run after building ρ, then the order is fixed
    sift_build: bool = False  # dynamic sifting while ρ is built, one run after, then fixed
    sift_above: int | None = SIFT_TRIGGER  # nodes a bit past which the build sifts anew;
    # never with pinned variables (``first``), whose order was chosen on purpose
    sift_blowup: float | None = SIFT_BLOWUP  # ρs / its clauses past which it is sifted once
    sift_after: float | None = None  # a refitted build's game sifts throughout after this
    # many seconds of fixpoint (the race's static racer: RACE_SIFT_AFTER)
    partitioned: bool = False  # ρs as clusters with early quantification (slow: see bench)
    recycle: bool = False  # start inner X fixpoints from the previous round's values (slower here)
    attractor: bool = True  # start each goal's μY from the system's attractor of the goal
    # (its rings need one CPre each, not an X fixpoint per assumption: Game._attractor)
    cluster_limit: int = 2500  # node limit when merging ρs parts into clusters
    memory_mb: int | None = None  # CUDD's hard memory limit (its own tables and caches)
    first: tuple[str, ...] = ()  # variables pinned to the top of the order (rigid parameters)
    restart_misfit: bool = False  # a misfit order raises OrderMisfit instead of sifting in
    # place (gaitc.solver.portfolio's small games, which then build again in the sifted order)


#: Of CUDD's memory budget (``Options.memory_mb``), the share at which the solver gives up:
#: near its limit CUDD stops growing its tables and collects garbage at every step, so the
#: operation that finally fails can come minutes later (a 30 x 30 grid at 100 MB: over 60 s).
MEMORY_STOP: Final = 0.9

