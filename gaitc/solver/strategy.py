"""Explicit Mealy strategy extraction from the stored layers of the GR(1) fixpoint.

Follows the construction of Bloem et al. (JCSS 2012, Sect. 5) as SLUGS implements it
(``extensionExtractExplicitStrategy``): per system goal j, prefer transitions that reach the
goal, else a lower Y ring, else stay in the X layer of an environment goal; the goal index
advances past every goal the chosen transition satisfies.  Nodes are (state, goal) pairs,
explored breadth-first from the initial states; among the allowed moves the preferences of
:mod:`gaitc.solver.preferences` choose, then the smallest assignment in the BDD's variable order.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from gaitc.diagnostics import SolverError
from gaitc.ir.bddwalk import Cofactors, State, all_assignments, cofactor, holds_at
from gaitc.ir.controller import Controller, ControllerKind, ControllerNode
from gaitc.ir.spec import Semantics
from gaitc.solver.canonical import (
    REPORT_EVERY,
    assignments,
    initial_states,
    primed,
    remembered,
    smallest,
    spec_integers,
)
from gaitc.solver.census import CENSUS_AFTER, CENSUS_SHARE, Census
from gaitc.solver.exploration import Exploration
from gaitc.solver.game import GameResult, Limits, goal_strategies, too_large
from gaitc.solver.steps import Steps, given
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

if TYPE_CHECKING:
    from gaitc.solver.preferences import MovePreferences


# ---------------------------------------------------------------- strategy
def next_goal(sym: SymbolicSpec, goal: int, move: dict[str, bool]) -> int:
    """Advance past every goal that ``move`` (a full pre/post assignment) satisfies."""
    n = len(sym.sys_live)
    current = goal
    first = True
    while (current != goal or first) and holds_at(sym.sys_live[current], move):
        current = (current + 1) % n
        first = False
    return current


def extract_strategy(
    sym: SymbolicSpec,
    result: GameResult,
    semantics: Semantics,
    limits: Limits | None = None,
    max_nodes: int | None = None,
    prefer: MovePreferences | None = None,
) -> Controller:
    """The explicit Mealy controller of a realizable game (``result`` needs its layers);
    ``prefer`` picks among the moves each step allows (:mod:`gaitc.solver.preferences`).

    With ``max_nodes``, an extraction still running after :data:`~gaitc.solver.census.
    CENSUS_AFTER` seconds counts its nodes on BDDs alongside (:class:`~gaitc.solver.census.
    Census`, given a third of the time from then on), and stops as soon as the count passes
    ``max_nodes``; until then it goes on as it would have."""
    limits = limits or Limits()
    ins, outs = list(sym.input_bits), list(sym.output_bits)
    pre = ins + outs
    post_in, post_out = primed(ins), primed(outs)
    post = post_in + post_out
    strategies = goal_strategies(sym, result)
    found: Exploration[tuple[State, int]] = Exploration("controller", max_nodes)

    def relation(goal: int) -> Steps[BDDNode]:
        moves = strategies[goal]
        return given(moves) if prefer is None else prefer.relation_steps(goal, moves)

    # Started after CENSUS_AFTER seconds: the move functions, then (with a node limit)
    # the count; the functions, once there, replace the per-input steps below.
    census: Census | None = Census(sym, relation, len(strategies), result.winning,
                                   semantics, max_nodes, counting=max_nodes is not None)
    expected: int | None = None  # the census's count, once it has one
    functions: list[BDDNode] | None = None  # the census's move functions, once it has them
    # CPU time of this thread, not the wall clock: the census's share of the work must not
    # depend on what else the machine runs.
    started = time.thread_time()
    initial = [found.number((s, 0)) for s in initial_states(sym, result.winning, semantics)]
    bdd = sym.bdd
    # The same few choices recur at state after state (one region and gait next, say):
    # their smallest move is found once (thesis 10 x 10 health 3: 7,974 choices, 106 kinds).
    smallest_of = remembered(lambda u: smallest(sym, u, post_out))
    # ρe and each goal's moves are cofactored at every state, and ρe again at every next
    # input, though each reads only some of those bits: Cofactors keeps each cofactor by the
    # values of the bits its BDD reads.  The key is sound: a cofactor cannot depend on a
    # variable outside the BDD's support, and BDDs are canonical, so the node kept is the
    # very node bdd.let returns for the whole state (the five-arm courier's extraction:
    # 3.2 s of CPU -> 2.8 s, the same controller: tests/solver/test_strategy_caches.py).
    moves_at = [Cofactors(bdd, s, pre) for s in strategies]
    env_at = Cofactors(bdd, sym.env_trans, pre)
    env_at_input = Cofactors(bdd, sym.env_trans, [*pre, *post_in])
    # The same few cofactors of ρe recur, so do the inputs they allow (a lift with 8 floors:
    # 12,032 states, 256 input sets).
    inputs_of = remembered(lambda u: assignments(sym, bdd.exist(sym.post_outputs, u), post_in))
    for k, (state, goal) in found:
        limits.check()
        if census is not None:
            spent = time.thread_time() - started
            if spent > CENSUS_AFTER and spent - CENSUS_AFTER > CENSUS_SHARE * census.seconds:
                expected = census.advance()
                functions = census.moves
                if expected is not None and max_nodes is not None and expected > max_nodes:
                    raise too_large("controller", max_nodes)
                if census.done:
                    census = None
        if k % REPORT_EVERY == 0:
            count = len(found.nodes)
            so_far = f"{count} of {expected}" if expected else f"{count}"
            limits.report("extracting the controller", f"{so_far} nodes found, "
                          f"{found.pending} to expand", k / (expected or count))
        at = dict(zip(pre, map(bool, state), strict=True))
        if functions is not None:
            moves = _moves_at(sym, bdd.let(at, functions[goal]), post, len(post_in))
        else:
            moves = _chosen_moves(
                sym=sym,
                at=at,
                goal=goal,
                here=moves_at[goal].at(at),
                inputs=inputs_of(env_at.at(at)),
                env=env_at_input,
                prefer=prefer,
                post_in=post_in,
                smallest_of=smallest_of,
            )
        targets = []
        for x, y in moves:
            move = at | dict(zip(post, map(bool, x + y), strict=True))
            targets.append(found.number((x + y, next_goal(sym, goal, move))))
        found.expanded(k, targets)
    return Controller(
        variables=tuple(pre),
        inputs=tuple(ins),
        outputs=tuple(outs),
        nodes=tuple(
            ControllerNode(goal, state, tuple(t))
            for (state, goal), t in zip(found.nodes, found.successors, strict=True)
        ),
        initial=tuple(sorted(set(initial))),
        integers=spec_integers(sym),
        kind=ControllerKind.STRATEGY,
        semantics=semantics,
    )


def _chosen_moves(sym: SymbolicSpec, at: dict[str, bool], goal: int, here: BDDNode,
                  inputs: list[State], env: Cofactors, *, prefer: MovePreferences | None,
                  post_in: Sequence[str], smallest_of: Callable[[BDDNode], State | None]
                  ) -> list[tuple[State, State]]:
    """The move (next input, next output) taken at the state ``at`` for goal ``goal``,
    one per input ρe allows there (``inputs``, sorted), in input order: the smallest of the
    preferred moves among ``here``, the goal's moves at the state (``env``: ρe's cofactors
    at a state and next input)."""
    bdd = sym.bdd
    if prefer is not None:
        here = prefer.allowed(at, goal, here)
    out = []
    for x in inputs:
        at_x = dict(zip(post_in, map(bool, x), strict=True))
        choices = cofactor(bdd, at_x, here)  # at_x is empty for a spec without inputs
        step = at | at_x
        preferred = choices & env.at(step)
        preferred = preferred if preferred != bdd.false else choices
        if prefer is not None and preferred != bdd.false:
            preferred = prefer.choose(step, goal, preferred)
        y = smallest_of(preferred)
        if y is None:
            raise SolverError(
                "internal error: the strategy has no move for an allowed input",
                hint="please report this specification",
            )
        out.append((x, y))
    return out


def _moves_at(sym: SymbolicSpec, here: BDDNode, post: Sequence[str],
              width: int) -> list[tuple[State, State]]:
    """:func:`_chosen_moves` read off a census's move function at the state (``here``, its
    cofactor there, over ``post``: the ``width`` primed inputs, then the primed outputs):
    the same moves, in the same order, found by one enumeration instead of a few BDD
    operations per input."""
    found = all_assignments(sym.bdd, here, post)
    moves = [(a[:width], a[width:]) for a in found]
    if len({x for x, _ in moves}) != len(moves):
        raise SolverError("internal error: a move function offers two moves for one input",
                          hint="please report this specification")
    return moves
