"""The environment's counter-strategy for an unrealizable spec, as an explicit automaton.

Dualises the GR(1) fixpoint of Bloem et al. (JCSS 2012) / SLUGS: the losing region is
μZ̄. ∨_j νȲ. ∧_i μX̄. EPre((¬J^s_j ∨ Z̄') ∧ Ȳ' ∧ (J^e_i ∨ X̄')) with
EPre(T) = ∃x'. ρe ∧ ∀y'. ρs → T (Könighofer, Hofferek, Bloem, FMCAD 2009 build the same
memory).  Nodes are (state, blocked system goal j, pursued environment goal i); the
environment picks one input per node (the smallest that makes progress) and every system
answer allowed by ρs becomes a successor.
"""

from __future__ import annotations

from dataclasses import dataclass

from gaitc.diagnostics import SolverError
from gaitc.ir.controller import Controller, ControllerKind, ControllerNode
from gaitc.ir.cuddlib import cudd
from gaitc.ir.spec import Semantics
from gaitc.solver.canonical import REPORT_EVERY, assignments, fix, primed, smallest, spec_integers
from gaitc.solver.exploration import Exploration
from gaitc.solver.game import Limits
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

State = tuple[int, ...]


@dataclass
class _Layer:
    """One step of μZ̄: the lower layer, per blocked goal j its Ȳ and the X̄ rings per i."""

    below: BDDNode
    ys: list[BDDNode]
    rings: list[list[list[BDDNode]]]  # rings[j][i][r], r = 0 is the first non-empty ring


class CounterGame:
    """The environment's side of the game of a :class:`SymbolicSpec`."""

    def __init__(self, sym: SymbolicSpec, limits: Limits) -> None:
        self.sym = sym
        self.limits = limits
        self.env_must = sym.bdd.forall(sym.post_outputs, sym.env_trans)
        # As in the system's game, EPre(T) only reads T inside the invariant, so the sets are
        # kept inside the care set and ρ is simplified outside it (SymbolicSpec._care_set).
        self.game_env_must = self.env_must
        if sym.care != sym.bdd.true and sym.care != sym.bdd.false:
            self.game_env_must = cudd.restrict(self.env_must, sym.care)
        self.layers: list[_Layer] = []

    def epre(self, target: BDDNode) -> BDDNode:
        """States where the environment has an input after which every ρs answer hits target."""
        sym = self.sym
        all_answers = ~cudd.and_exists(sym.game_sys_trans, ~target, sym.post_outputs)
        return cudd.and_exists(self.game_env_must, all_answers, sym.post_inputs) & sym.care

    def _guard(self, j: int, below: BDDNode, y: BDDNode) -> BDDNode:
        sym = self.sym
        return (~sym.sys_live[j] | sym.prime(below)) & sym.prime(y)

    def solve(self) -> BDDNode:
        """The losing region of the system, layer by layer (kept in ``self.layers``)."""
        sym, bdd = self.sym, self.sym.bdd
        zbar = bdd.false
        while True:
            layer = _Layer(zbar, [], [])
            new = bdd.false
            for j in range(len(sym.sys_live)):
                y = sym.care
                while True:
                    self.limits.check()
                    guard = self._guard(j, zbar, y)
                    all_rings = []
                    next_y = sym.care
                    for i in range(len(sym.env_live)):
                        x = bdd.false
                        rings = []
                        while True:
                            self.limits.check()
                            new_x = self.epre(guard & (sym.env_live[i] | sym.prime(x)))
                            if new_x == x:
                                break
                            rings.append(new_x)
                            x = new_x
                        all_rings.append(rings)
                        next_y &= x
                    if next_y == y:
                        break
                    y = next_y
                layer.ys.append(y)
                layer.rings.append(all_rings)
                new |= y
            if new == zbar:
                return zbar
            self.layers.append(layer)
            zbar = new

    # ------------------------------------------------------------ explicit extraction
    def _contains(self, u: BDDNode, state: State) -> bool:
        sym = self.sym
        return bool(fix(sym, u, sym.input_bits + sym.output_bits, state) == sym.bdd.true)

    def layer_of(self, state: State) -> int:
        for k, layer in enumerate(self.layers):
            if any(self._contains(y, state) for y in layer.ys):
                return k
        raise SolverError("internal error: a counter-strategy state is not losing for the system")

    def memory(self, state: State, previous: tuple[int, int, int] | None) -> tuple[int, int]:
        """The (blocked goal, environment goal) a node at ``state`` pursues."""
        k = self.layer_of(state)
        layer = self.layers[k]
        if previous is not None:
            k0, j0, i0 = previous
            if k0 == k and self._contains(layer.ys[j0], state):
                return j0, i0
        j = next(j for j, y in enumerate(layer.ys) if self._contains(y, state))
        return j, 0


def extract_counterstrategy(
    sym: SymbolicSpec,
    winning: BDDNode,
    semantics: Semantics,
    limits: Limits | None = None,
    max_nodes: int | None = None,
) -> Controller:
    """The environment's explicit winning strategy (``winning`` is the system's region)."""
    limits = limits or Limits()
    game = CounterGame(sym, limits)
    losing = game.solve()
    if losing & sym.care != ~winning & sym.care:  # the game is exact on its care set
        raise SolverError("internal error: the dual fixpoint disagrees with the winning region")
    ins, outs = list(sym.input_bits), list(sym.output_bits)
    pre = ins + outs
    post_in, post_out = primed(ins), primed(outs)
    found: Exploration[tuple[State, int, int]] = Exploration("counter-strategy", max_nodes)

    def node_of(state: State, previous: tuple[int, int, int] | None) -> int:
        j, i = game.memory(state, previous)
        return found.number((state, j, i))

    initial: list[int] = []
    if semantics == Semantics.ROBOTICS:
        start = smallest(sym, sym.env_init & sym.sys_init & losing, pre)
        if start is not None:
            initial.append(node_of(start, None))
    else:
        sys_can_win = sym.bdd.exist(sym.pre_outputs, sym.sys_init & winning)
        x = smallest(sym, sym.env_init & ~sys_can_win, ins)
        if x is not None:
            for y in assignments(sym, fix(sym, sym.sys_init, ins, x), outs):
                initial.append(node_of(x + y, None))
    for n, (state, j, i) in found:
        limits.check()
        if n % REPORT_EVERY == 0:
            limits.report("extracting the counter-strategy", f"{len(found.nodes)} nodes found, "
                          f"{found.pending} to expand", n / len(found.nodes))
        k = game.layer_of(state)
        layer = game.layers[k]
        rings = layer.rings[j][i]
        r = next(r for r, ring in enumerate(rings) if game._contains(ring, state))
        lower = rings[r - 1] if r > 0 else sym.bdd.false
        target = game._guard(j, layer.below, layer.ys[j]) & (sym.env_live[i] | sym.prime(lower))
        all_answers = ~cudd.and_exists(sym.sys_trans, ~target, sym.post_outputs)
        choice = fix(sym, game.env_must & all_answers, pre, state)
        x = smallest(sym, sym.bdd.exist(sym.post_outputs, choice), post_in)
        if x is None:
            raise SolverError("internal error: the environment has no winning move")
        step = fix(sym, fix(sym, sym.sys_trans, pre, state), post_in, x)
        targets = []
        for y in assignments(sym, step, post_out):
            move = {
                b: bool(v) for b, v in zip(pre + post_in + post_out, state + x + y, strict=True)
            }
            met = sym.bdd.let(move, sym.env_live[i]) == sym.bdd.true
            nxt = (k, j, (i + 1) % len(sym.env_live) if met else i)
            targets.append(node_of(x + y, nxt))
        found.expanded(n, targets)
    return Controller(
        variables=tuple(pre),
        inputs=tuple(ins),
        outputs=tuple(outs),
        nodes=tuple(
            ControllerNode(i, state, tuple(t))
            for (state, _, i), t in zip(found.nodes, found.successors, strict=True)
        ),
        initial=tuple(sorted(set(initial))),
        integers=spec_integers(sym),
        kind=ControllerKind.COUNTERSTRATEGY,
        semantics=semantics,
    )
