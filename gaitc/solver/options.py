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

#: A fixpoint step's work is counted in CUDD's computed-table lookups (one per recursive
#: call of an operation), a count that does not depend on the machine's speed or load; the
#: solver reads it at sample steps only (:data:`WORK_SAMPLES`), since reading CUDD's
#: statistics scans its tables (0.36 ms).  Measured: 110-450 ns a lookup on this machine,
#: so 200,000 lookups are about 50 ms of work.
#:
#: After a restart (or a build sifted once) the fixpoint runs in the sifted order, fixed,
#: until its steps average more than this many lookups between two samples; then CUDD's
#: sifting is turned on for the rest of the game (``Game.resume_sifting``).  Measured on the
#: AMBA arbiters, solve only: a fixed order wins up to 6 masters (1,600 lookups a step at 5
#: masters, a slowest step of 60,000), sifting from 8 masters on (slowest steps 0.1-1.3 s).
RESIFT_WORK: Final = 200_000

#: After a refitted build, the game of the plan's static run (``Options.refit_sift``) sifts
#: throughout once its steps have done this many lookups in all (about 0.3 s of work),
#: whether or not one step was slow: the order was
#: sifted for ρ, and the fixpoint's sets outgrow it (the race's static racer did this
#: after 0.3 s of fixpoint until issue 50; measured there: GenBuf with 24 senders 3.3 s
#: against 6.4 s fixed, AMBA bit-encoded with 3 masters 0.96 s against 1.15 s, AMBA with
#: 6 masters 1.19 s against 0.94 s).
REFIT_SIFT_WORK: Final = 1_200_000

#: The steps after which the work counter is read: 1, 2, 4, 8, 16, then every 32 steps.
WORK_SAMPLES: Final = (1, 2, 4, 8, 16)
WORK_EVERY: Final = 32

#: A game in the static order, not refitted, whose steps have done more than MISFIT_WORK
#: lookups in all, at over MISFIT_RATIO lookups per node of their targets and results,
#: misfits its sets: it is built again with CUDD's sifting throughout
#: (:class:`~gaitc.solver.game.OrderMisfit`, ``dynamic``).  Measured, the ratio at 4
#: million lookups: SLUGS's EvasionOnGrid example 4.4 (its sets want the request bits on
#: top and each axis's flags beside the axis: 186 s in the static order, 54 s sifting
#: throughout, about 1 s lost to the judgement); gridworld 1024 x 1024 0.35; the thesis
#: grids 0.3-0.9 and under 2 million lookups in all; the hazard grids 2.4 and under 0.3
#: million.  Sifting in place from the static order's sets instead found a worse order
#: (221 s).
MISFIT_WORK: Final = 4_000_000
MISFIT_RATIO: Final = 3.0

#: Specs of at most this many state bits are solved in this process in the static order,
#: without a race (gaitc.solver.portfolio): no set of states over 20 bits has more than 2^20 BDD
#: nodes and the build restarts before a partial relation passes 8,000 (SIFT_TRIGGER a
#: bit).  Steps of such a game that average more than SMALL_WORK lookups show that its
#: order misfits, and sifting 40 variables is cheap: the moving obstacle 8 x 8 (18 bits)
#: has steps of 0.02-0.07 s in the guards order, 1.0 s to solve fixed and 0.2 s sifting;
#: the SLUGS examples and random-corpus specs this small take at most 0.004 s a step
#: (thesis robots A and B have 27 bits and more).
SMALL_BITS: Final = 20
SMALL_WORK: Final = 40_000
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
    partitioned: bool = False  # ρs as clusters with early quantification (slow: see bench)
    recycle: bool = False  # start inner X fixpoints from the previous round's values (slower here)
    attractor: bool = True  # start each goal's μY from the system's attractor of the goal
    # (its rings need one CPre each, not an X fixpoint per assumption: Game._attractor)
    cluster_limit: int = 2500  # node limit when merging ρs parts into clusters
    memory_mb: int | None = None  # CUDD's hard memory limit (its own tables and caches)
    first: tuple[str, ...] = ()  # variables pinned to the top of the order (rigid parameters)
    refit_sift: bool = False  # a refitted build's game sifts throughout after REFIT_SIFT_WORK
    # lookups of fixpoint (the plan's static run, gaitc.solver.portfolio)
    rebuild_misfit: bool = False  # a game working too hard for its sets raises OrderMisfit
    # (dynamic) for its caller to build it again sifting throughout (gaitc.solver.portfolio)
    restart_misfit: bool = False  # a misfit order raises OrderMisfit instead of sifting in
    # place (gaitc.solver.portfolio's small games, which then build again in the sifted order)


#: Of CUDD's memory budget (``Options.memory_mb``), the share at which the solver gives up:
#: near its limit CUDD stops growing its tables and collects garbage at every step, so the
#: operation that finally fails can come minutes later (a 30 x 30 grid at 100 MB: over 60 s).
MEMORY_STOP: Final = 0.9

