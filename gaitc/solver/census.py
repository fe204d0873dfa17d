"""How many nodes an explicit extraction will make, counted on BDDs before it makes them.

:func:`gaitc.solver.strategy.extract_strategy` explores (state, goal) pairs breadth-first, one
input at a time, taking the smallest allowed move in the static bit order; on a spec with
many free inputs it makes a few hundred nodes a second.  The same controller can be counted
symbolically: each goal's move relation is narrowed to its smallest move per state and
input (a lexicographic minimum, one output bit at a time), the goal counter's advance is a
formula over the move (:func:`advances`), and a breadth-first image computation over the
sets of nodes per goal yields every node the extraction would reach.  The count lets a run
that asked for at most ``max_nodes`` nodes give up (or turn symbolic) in seconds instead of
after the ``max_nodes``-th node, and it is exact, so it also tells how far an extraction
has got.  The images are those of symbolic reachability (Burch et al., "Symbolic model
checking: 10^20 states and beyond", 1992) on the controller's own transition relation.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Final

from gaitc.ir.cuddlib import cudd
from gaitc.ir.spec import Semantics
from gaitc.solver.steps import Steps, given, run_through
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

#: An extraction with a node limit that has run this many CPU seconds starts its census; a
#: shorter one never pays for it (thesis robot A extracts in 0.3-1 s; its census, whose
#: preference relations carry the robot model's costs, takes 10-40 s).
CENSUS_AFTER: Final = 2.0
#: From then on the extraction spends this many CPU seconds for each second of the census
#: (the census gets a quarter of the time).
CENSUS_SHARE: Final = 3.0


def smallest_moves(sym: SymbolicSpec, moves: BDDNode, bits: Sequence[str],
                   over: set[str]) -> Steps[BDDNode]:
    """``moves`` narrowed (in steps) to its smallest assignment to ``bits`` (the variables ``over``,
    ranked by :attr:`SymbolicSpec.choice_rank`, first bit most significant, 0 before 1) at
    every assignment to the other variables: :func:`gaitc.ir.bddwalk.first_assignment` for all
    of them at once."""
    bdd = sym.bdd

    def rank(bit: str) -> int:
        return sym.choice_rank[bit[:-1] if bit in sym.unprime_map else bit]

    for bit in sorted(bits, key=rank):
        zero = ~bdd.var(bit)
        has_zero = bdd.exist(over, moves & zero)
        moves &= zero | ~has_zero
        yield
    return moves


def advances(sym: SymbolicSpec) -> list[list[BDDNode]]:
    """``advances(sym)[j][g]``: the moves after which goal ``j`` gives way to goal ``g``, as
    :func:`gaitc.solver.strategy.next_goal` advances the counter past every goal a move meets
    (and keeps ``j`` when the move meets them all)."""
    goals = list(sym.sys_live)
    n = len(goals)
    out = []
    for j in range(n):
        to = [sym.bdd.false] * n
        met = sym.bdd.true
        for step in range(n):
            g = (j + step) % n
            to[g] = met & ~goals[g]
            met &= goals[g]
        to[j] |= met
        out.append(to)
    return out


def initial_nodes(sym: SymbolicSpec, winning: BDDNode, semantics: Semantics) -> BDDNode:
    """The states of :func:`gaitc.solver.canonical.initial_states`, as one BDD."""
    if semantics == Semantics.ROBOTICS:
        return sym.env_init & sym.sys_init & winning
    outs = list(sym.output_bits)
    chosen = run_through(smallest_moves(sym, sym.sys_init & winning, outs, sym.pre_outputs))
    return sym.bdd.exist(sym.pre_outputs, sym.env_init) & chosen


def node_count(sym: SymbolicSpec, relations: Sequence[BDDNode], winning: BDDNode,
               semantics: Semantics, cap: int | None = None) -> int:
    """The number of nodes :func:`gaitc.solver.strategy.extract_strategy` makes when goal ``j``
    moves by ``relations[j]`` (after the preferences; over the state and the primed inputs
    and outputs); once the count passes ``cap`` the search stops and returns what it has."""
    census = Census(sym, lambda j: given(relations[j]), len(relations), winning, semantics,
                    cap)
    while not census.done:
        census.advance()
    return census.count or 0


def move_functions(sym: SymbolicSpec, relation: Callable[[int], Steps[BDDNode]],
                   goals: int) -> Steps[list[BDDNode]]:
    """Per goal ``j``, the move the extraction takes at every state and input ρe allows, as
    one BDD over the state and the primed inputs and outputs: ``relation(j)`` (computed in
    steps) within ρe, narrowed to its smallest move (:func:`smallest_moves`).  At a state,
    its cofactor holds exactly one move per allowed input."""
    out = []
    for j in range(goals):
        moves = (yield from relation(j)) & sym.env_trans
        yield
        out.append((yield from smallest_moves(sym, moves, sorted(sym.post_outputs),
                                              sym.post_outputs)))
    return out


class Census:
    """:func:`node_count` in slices, each a few BDD operations, so that an extraction can
    run it alongside itself and give it a share of its own time; ``relation(j)`` computes
    goal ``j``'s move relation, in steps too, when the census needs it.

    Its first slices compute :func:`move_functions`, kept in :attr:`moves` once done: an
    extraction can then read each node's moves off them (:func:`gaitc.solver.strategy.
    extract_strategy`).  With ``counting`` False the census ends there, with no count."""

    def __init__(self, sym: SymbolicSpec, relation: Callable[[int], Steps[BDDNode]], goals: int,
                 winning: BDDNode, semantics: Semantics, cap: int | None = None,
                 counting: bool = True) -> None:
        self.count: int | None = None
        self.moves: list[BDDNode] | None = None
        self.done = False
        self.seconds = 0.0
        self._slices = self._census(sym, relation, goals, winning, semantics, cap, counting)

    def advance(self) -> int | None:
        """Run one slice; the count once the census is done, else None."""
        started = time.thread_time()
        try:
            next(self._slices)
        except StopIteration as done:
            self.count = done.value
            self.done = True
        finally:
            self.seconds += time.thread_time() - started
        return self.count

    def _census(self, sym: SymbolicSpec, relation: Callable[[int], Steps[BDDNode]], n: int,
                winning: BDDNode, semantics: Semantics, cap: int | None,
                counting: bool) -> Steps[int | None]:
        """The census itself, a slice per step."""
        steps = self.moves = yield from move_functions(sym, relation, n)
        if not counting:
            return None
        bdd = sym.bdd
        pre = sym.pre_inputs | sym.pre_outputs
        width = len(pre)
        to = advances(sym)
        reached = [bdd.false] * n
        frontier = [bdd.false] * n
        frontier[0] = initial_nodes(sym, winning, semantics)
        total = 0
        while any(f != bdd.false for f in frontier):
            for g in range(n):
                reached[g] |= frontier[g]
            total += sum(int(bdd.count(f, nvars=width)) for f in frontier)  # new nodes only
            if cap is not None and total > cap:
                return total
            found = [bdd.false] * n
            for j, part in enumerate(frontier):
                if part == bdd.false:
                    continue
                moved = part & steps[j]
                for g in range(n):
                    found[g] |= sym.unprime(cudd.and_exists(moved, to[j][g], pre))
                    yield
            frontier = [found[g] & ~reached[g] for g in range(n)]
        return total
