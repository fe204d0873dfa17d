"""From a solved game's strategy relations to the smallest compact controller found.

Input: the roots of a symbolic controller (:mod:`gaitc.ir.bddfile`): the winning region W,
ρe, θe, θs, the goals and per goal j the relation S_j of moves that make progress towards
goal j.  For goal j the care set is W ∧ ρe ∧ ∃y'.S_j: every state a run can be in, with every
input the assumptions allow; outside it the function may do anything.  Each candidate field
order (:data:`ORDERS`) gives one diagram per goal, the goal diagrams and the start diagram
in one shared table; the order with the fewest decision nodes wins (the analogue of dynamic
reordering, over a handful of orders that put the robot's own state first).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, Final

from gaitc.compact.controller import CompactController, relations
from gaitc.compact.diagram import DONT_CARE, Builder, Ref, Slot, leaf, reachable_nodes
from gaitc.core.vocabulary import Vocabulary
from gaitc.diagnostics.choices import Choice
from gaitc.ir.bddfile import SymbolicController, declare, materialize
from gaitc.ir.manager import manager
from gaitc.ir.spec import Semantics

if TYPE_CHECKING:
    from dd.cudd import BDD, Function


class FieldOrder(Choice):
    """How a diagram picks the field each node reads: by lookahead (``greedy``), or in a
    fixed order, the robot's outputs first, then the inputs just chosen and the current
    ones (``outputs-first``; ``inputs-reversed`` takes the inputs last to first)."""

    GREEDY = "greedy"
    OUTPUTS_FIRST = "outputs-first"
    INPUTS_REVERSED = "inputs-reversed"


#: The orders tried by default (the fixed ones are faster, rarely smaller).
ORDERS: Final = (FieldOrder.GREEDY,)
#: At most this many rounds of shrinking the care sets (each usually halves the gain).
ROUNDS: Final = 4


def slot_order(vocabulary: Vocabulary, how: FieldOrder) -> list[Slot]:
    """The slots in the order a fixed-order diagram reads them.  ``greedy`` puts each input's
    new value next to its current one, the order in which ρe (a conjunction over inputs,
    each relating a value to the next) has a small diagram."""
    outs = [Slot(f) for f in vocabulary.outputs]
    if how == FieldOrder.GREEDY:
        return outs + [s for f in vocabulary.inputs for s in (Slot(f, True), Slot(f))]
    chosen = [Slot(f, True) for f in vocabulary.inputs]
    now = [Slot(f) for f in vocabulary.inputs]
    if how == FieldOrder.INPUTS_REVERSED:
        chosen.reverse()
        now.reverse()
    return outs + chosen + now


@dataclass(frozen=True)
class Game:
    """A solved game's roots (dd.cudd functions of ``bdd`` over ``inputs``, ``outputs`` and
    their primed copies), named as in :data:`gaitc.ir.bddfile.SINGLE_ROOTS`."""

    bdd: BDD
    roots: Mapping[str, Any]  # a node, or a list of them per goal (gaitc.ir.bddfile.materialize)
    inputs: tuple[str, ...]
    outputs: tuple[str, ...]
    semantics: Semantics


def compact_from_roots(game: Game, vocabulary: Vocabulary,
                       orders: Sequence[FieldOrder] = ORDERS) -> CompactController:
    """The compact controller of ``game``, the smallest of ``orders``."""
    best: CompactController | None = None
    for how in orders:
        found = _one_order(game, vocabulary, slot_order(vocabulary, how),
                           how == FieldOrder.GREEDY)
        if best is None or found.decision_nodes < best.decision_nodes:
            best = found
    assert best is not None
    return best


def _one_order(game: Game, vocabulary: Vocabulary, slots: list[Slot], greedy: bool = False
               ) -> CompactController:
    """The diagrams for one field order, shrunk round by round: each round's care sets are
    the states the previous round's function reaches, and its moves may only lead into
    them, so the sets stay closed while they shrink (until the size stops falling)."""
    bdd, roots, inputs, outputs = game.bdd, game.roots, game.inputs, game.outputs
    semantics = game.semantics
    prime = {b: b + "'" for b in (*inputs, *outputs)}
    winning, env_trans = roots["winning"], roots["env_trans"]
    post_out = {b + "'" for b in outputs}
    strategies = list(roots["strategies"])
    moving = counter_moves(bdd, roots["goals"])
    start_ok = roots["sys_init"] & winning
    if semantics == Semantics.ROBOTICS:
        init = roots["env_init"] & start_ok
    else:
        init = bdd.exist(set(outputs), roots["env_init"]) & start_ok
    reach = reachable(bdd, init, strategies, env_trans, moving, inputs, outputs)
    allowed, first_ok = strategies, start_ok
    best: tuple[CompactController, Builder, Function] | None = None
    for _ in range(ROUNDS):
        builder = Builder(bdd, slots, vocabulary.outputs, greedy=greedy)
        move_roots = [_defined(builder.build_moves(here & env_trans
                                                   & bdd.exist(post_out, relation), relation))
                      for here, relation in zip(reach, allowed, strict=True)]
        anywhere = bdd.false
        for here in reach:
            anywhere |= here
        reached_roots = [_defined(builder.build_boolean(anywhere, goal), leaf(1))
                         for goal in roots["goals"]]
        if semantics == Semantics.ROBOTICS:
            start = _defined(builder.build_boolean(bdd.true, init), leaf(0))
        else:
            first = bdd.exist(set(outputs), init)
            start = _defined(builder.build_moves(bdd.let(prime, first),
                                                 bdd.let(prime, first_ok)))
        found = CompactController(
            vocabulary=vocabulary, slots=tuple(slots), nodes=tuple(builder.nodes),
            moves=tuple(builder.moves), move_roots=tuple(move_roots),
            reached_roots=tuple(reached_roots), start_root=start, assumed_root=leaf(1),
            inputs=tuple(inputs),
            outputs=tuple(outputs), semantics=semantics)
        if best is not None and found.decision_nodes >= best[0].decision_nodes:
            break
        best = found, builder, anywhere
        made = relations(bdd, found)
        begin = init if semantics == Semantics.ROBOTICS else made["start"]
        shrunk = reachable(bdd, begin, made["strategies"], env_trans, moving, inputs, outputs)
        if shrunk == reach:
            break
        reach = shrunk
        allowed = []
        for j, relation in enumerate(strategies):
            into = bdd.false
            for k, here in enumerate(reach):
                into |= moving[j][k] & bdd.let(prime, here)
            allowed.append(relation & into)
        first_ok = start_ok & reach[0]
    assert best is not None
    found, builder, anywhere = best
    builder.greedy = False  # in slot order, where each input's values sit side by side
    # the monitor must equal ρe on every state a run reaches (the verifier proves it); the
    # diagram of ρe on every state the fields name often is smaller, being more regular
    candidates = [_defined(builder.build_boolean(care, env_trans), leaf(1))
                  for care in (anywhere, field_domain(bdd, slots))]
    sizes = [len(reachable_nodes(builder.nodes, [*found.roots[:-1], root]))
             for root in candidates]
    chosen = candidates[sizes.index(min(sizes))]
    return pruned(replace(found, nodes=tuple(builder.nodes), assumed_root=chosen))


def pruned(ctrl: CompactController) -> CompactController:
    """``ctrl`` with only the nodes some root reaches, renumbered children first."""
    kept = reachable_nodes(ctrl.nodes, ctrl.roots)
    number = {old: new for new, old in enumerate(kept)}

    def ref(r: Ref) -> Ref:
        return r if r < 0 else number[r]

    nodes = tuple(replace(ctrl.nodes[old], kids=tuple(ref(k) for k in ctrl.nodes[old].kids))
                  for old in kept)
    return replace(ctrl, nodes=nodes, move_roots=tuple(ref(r) for r in ctrl.move_roots),
                   reached_roots=tuple(ref(r) for r in ctrl.reached_roots),
                   start_root=ref(ctrl.start_root),
                   assumed_root=None if ctrl.assumed_root is None else ref(ctrl.assumed_root))


def field_domain(bdd: BDD, slots: Sequence[Slot]) -> Function:
    """The states (and chosen inputs) the slots can name: every field at one of its values."""
    out = bdd.true
    for slot in slots:
        values = bdd.false
        for k in range(len(slot.field.labels)):
            values |= bdd.cube(slot.field.cube(k, slot.next))
        out &= values
    return out


def counter_moves(bdd: BDD, goals: Sequence[Function]) -> list[list[Function]]:
    """``moving[j][k]``: the states after which the goal counter goes from j to k (goals
    j..k-1 hold there and k does not; or every goal holds and it stays at j)."""
    n = len(goals)
    moving: list[list[Function]] = []
    for j in range(n):
        row, met = [bdd.false] * n, bdd.true
        for t in range(n):
            k = (j + t) % n
            row[k] |= met & ~goals[k]
            met &= goals[k]
        row[j] |= met
        moving.append(row)
    return moving


def reachable(bdd: BDD, init: Function, strategies: Sequence[Function], env_trans: Function,
              moving: Sequence[Sequence[Function]], inputs: Sequence[str],
              outputs: Sequence[str]) -> list[Function]:
    """Per goal j, the states a run can be in while it pursues goal j when the controller
    may make any move of ``strategies[j]``, from ``init`` at goal 1: the care sets.  Closed
    under every move allowed, so a function that picks any of them never leaves them."""
    starts = [init if j == 0 else bdd.false for j in range(len(strategies))]
    return reachable_from(bdd, starts, strategies, env_trans, moving, inputs, outputs)


def reachable_from(bdd: BDD, starts: Sequence[Function], strategies: Sequence[Function],
                   env_trans: Function, moving: Sequence[Sequence[Function]],
                   inputs: Sequence[str], outputs: Sequence[str]) -> list[Function]:
    """:func:`reachable` from ``starts[j]`` pursuing goal j, for every j (a recovery lands a
    run in the middle of a goal, :mod:`gaitc.compact.recovery`)."""
    pre = set(inputs) | set(outputs)
    unprime = {b + "'": b for b in pre}
    n = len(strategies)
    reach = [bdd.false] * n
    frontier = list(starts)
    while any(f != bdd.false for f in frontier):
        for j in range(n):
            reach[j] |= frontier[j]
        found = [bdd.false] * n
        for j in range(n):
            if frontier[j] == bdd.false:
                continue
            steps = frontier[j] & env_trans & strategies[j]
            for k in range(n):
                if moving[j][k] != bdd.false:
                    found[k] |= bdd.let(unprime, bdd.exist(pre, steps & moving[j][k]))
        frontier = [found[k] & ~reach[k] for k in range(n)]
    return reach


def _defined(ref: int, otherwise: int | None = None) -> int:
    """A root whose care set is empty (no state needs it) points to any leaf."""
    if ref != DONT_CARE:
        return ref
    return otherwise if otherwise is not None else leaf(0)


def compact_from_symbolic(ctrl: SymbolicController, vocabulary: Vocabulary,
                          orders: Sequence[FieldOrder] = ORDERS) -> CompactController:
    """The compact controller of a stored symbolic controller."""
    bdd = manager()
    declare(bdd, ctrl)
    roots = materialize(bdd, ctrl)
    found = compact_from_roots(Game(bdd, roots, ctrl.inputs, ctrl.outputs, ctrl.semantics),
                               vocabulary, orders)
    return replace(found, integers=dict(ctrl.integers), solver=ctrl.solver, source=ctrl.source)
