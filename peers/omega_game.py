"""gaitc's GR(1) IR as an omega game, solved by omega's own GR(1) fixpoint.

References: omega's ``omega/games/gr1.py`` (``solve_streett_game``, ``is_realizable``) and
``omega/symbolic/fixpoint.py`` (``step``); Bloem et al., "Synthesis of Reactive(1)
designs", JCSS 78(3), 2012.

The automaton.  Each variable is declared to omega as itself, an integer with its range or
a Boolean, under the name ``v<k>_<name>`` (an identifier omega reads, never one of its
keywords); omega bit-blasts the integers.  Each formula becomes a BDD bottom up, every
shared node once: Boolean operators as BDD operations, each comparison handed to omega's
parser as one small expression (omega's integer arithmetic is exact: its bit vectors widen
for sums).  omega's type invariants give the ranges as gaitc's and SLUGS's bit-blasting
does: the inputs' on θe and their next values' on ρe, the outputs' on θs and ρs.  Liveness
is over one state, as :mod:`peers.game` makes it.  The game is set as SLUGS plays it:
``moore = False`` (the system sees the next inputs before it moves) and ``plus_one = False``
(a step is ρe → ρs ∧ Z', so a move outside ρe wins for the system); the winning condition
is ``<>[]`` of each environment goal's complement (``[FALSE]`` without goals) or ``[]<>``
of each system goal (``[TRUE]`` without goals), the GR(1) implication.

The initial condition maps onto omega's ``qinit`` exactly.  For the default semantics,
``\\A \\E`` with ``plus_one = False`` asks ∀x. ∃y. (θs ∧ W) ∨ ¬θe; θe is over inputs only
(:mod:`peers.game` checks it), so that is ∀x. θe → ∃y. θs ∧ W, gaitc's condition.  For the
robotics semantics, ``\\A \\A`` asks ∀x, y. EnvInit → W with SysInit TRUE; EnvInit is
θe ∧ θs, so that is gaitc's ∀x, y. θe ∧ θs → W.

``python -m peers.omega_game FILE [--semantics robotics]`` decides one SLUGS file in a
process of its own (what the benchmarks time) and prints ``realizable`` (exit 0) or
``unrealizable`` (exit 3); a file it cannot read or translate exits 1.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import re
import sys
from typing import Any

from gaitc.diagnostics import GaitcError, render_error
from gaitc.ir.formula import (
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Term,
    Var,
    Xor,
    node_kind,
    term_kind,
    unreachable,
)
from gaitc.ir.spec import SEMANTICS, GR1Spec, Semantics, semantics_named
from gaitc.ir.traversal import Memo, Node, fold
from peers.game import peer_game
from slugs_bridge.formats import load_spec_file

#: omega's ``qinit`` for each semantics (see the module's docstring).
QINIT = {Semantics.DEFAULT: r"\A \E", Semantics.ROBOTICS: r"\A \A"}


def omega_names(spec: GR1Spec) -> dict[str, str]:
    """The name omega reads for each variable: ``v<k>_`` and the name's identifier
    characters (distinct by ``k``; no omega keyword starts so)."""
    return {v.name: f"v{k}_" + re.sub(r"[^A-Za-z0-9_]", "_", v.name)
            for k, v in enumerate(spec.variables())}


class _Builder:
    """The BDDs of one spec's formulas in one omega automaton."""

    def __init__(self, aut: Any, names: dict[str, str]) -> None:
        self.aut = aut
        self.names = names
        self.memo: Memo[Any] = {}

    def bdd(self, expr: Expr) -> Any:
        return fold(expr, self._node, children=_formula_children, memo=self.memo)

    def conj(self, exprs: list[Expr]) -> Any:
        out = self.aut.true
        for expr in exprs:
            out &= self.bdd(expr)
        return out

    def _node(self, node: Node, kids: list[Any]) -> Any:
        kind = node_kind(node)
        aut = self.aut
        match kind:
            case Const():
                return aut.true if kind.value else aut.false
            case Var():
                return aut.add_expr(self._name(kind.name, kind.primed))
            case Not():
                return ~kids[0]
            case And():
                out = aut.true
                for kid in kids:
                    out &= kid
                return out
            case Or():
                out = aut.false
                for kid in kids:
                    out |= kid
                return out
            case Xor():
                return ~kids[0].equiv(kids[1])
            case Iff():
                return kids[0].equiv(kids[1])
            case Implies():
                return kids[0].implies(kids[1])
            case Compare():
                op = "#" if kind.op == "!=" else kind.op
                return aut.add_expr(f"({self._term(kind.left)}) {op} ({self._term(kind.right)})")
            case IntConst() | IntVar() | Add() | Next() | Always() | Eventually():
                raise AssertionError(f"no {type(kind).__name__} in a GR(1) section's formula")
            case _:
                unreachable(kind)

    def _name(self, name: str, primed: bool) -> str:
        return self.names[name] + ("'" if primed else "")

    def _term(self, term: Term) -> str:
        def piece(node: Node, kids: list[str]) -> str:
            kind = term_kind(node)
            match kind:
                case IntConst():
                    return f"({kind.value})" if kind.value < 0 else str(kind.value)
                case IntVar():
                    return self._name(kind.name, kind.primed)
                case Add():
                    return f"({kids[0]} + {kids[1]})"
                case _:
                    unreachable(kind)

        return fold(term, piece)


def _formula_children(node: Node) -> tuple[Node, ...]:
    """A comparison is a leaf: omega reads it whole."""
    return () if isinstance(node, Compare) else node.children()


def build_automaton(spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT) -> Any:
    """omega's ``temporal.Automaton`` for ``spec`` under ``semantics``, ready for
    ``omega.games.gr1.solve_streett_game`` (see the module's docstring)."""
    from omega.symbolic import temporal  # lazy: the peers extra (omega) may be missing

    game = peer_game(spec)
    names = omega_names(game)
    aut = temporal.Automaton()
    declared = {names[v.name]: "bool" if v.low is None or v.high is None else (v.low, v.high)
                for v in game.variables()}
    if declared:
        aut.declare_variables(**declared)
    inputs = [names[v.name] for v in game.inputs]
    outputs = [names[v.name] for v in game.outputs]
    aut.varlist = {"env": inputs, "sys": outputs}
    aut.moore = False
    aut.plus_one = False
    aut.qinit = QINIT[semantics]
    build = _Builder(aut, names)

    def ranges(variables: list[str], primed: bool) -> Any:
        listed = [name + "'" for name in variables] if primed else variables
        text = aut.type_hint_for(listed)
        return aut.add_expr(text) if text else aut.true

    env_init = build.conj([c.formula for c in game.env_init]) & ranges(inputs, False)
    sys_init = build.conj([c.formula for c in game.sys_init]) & ranges(outputs, False)
    if semantics == Semantics.ROBOTICS:
        aut.init["env"], aut.init["sys"] = env_init & sys_init, aut.true
    else:
        aut.init["env"], aut.init["sys"] = env_init, sys_init
    aut.action["env"] = build.conj([c.formula for c in game.env_trans]) & ranges(inputs, True)
    aut.action["sys"] = build.conj([c.formula for c in game.sys_trans]) & ranges(outputs, True)
    aut.win["<>[]"] = [~build.bdd(c.formula) for c in game.env_liveness] or [aut.false]
    aut.win["[]<>"] = [build.bdd(c.formula) for c in game.sys_liveness] or [aut.true]
    return aut


def decide(spec: GR1Spec, semantics: Semantics = Semantics.DEFAULT) -> bool:
    """Whether ``spec`` is realizable under ``semantics``, by omega's GR(1) solver."""
    from omega.games import gr1  # lazy: the peers extra (omega) may be missing

    aut = build_automaton(spec, semantics)
    winning, _, _ = gr1.solve_streett_game(aut)
    with contextlib.redirect_stdout(io.StringIO()):  # it prints why a spec is unrealizable
        return bool(gr1.is_realizable(winning, aut))


def main(argv: list[str] | None = None) -> int:
    """``python -m peers.omega_game FILE [--semantics S]``: 0 realizable, 3 unrealizable,
    1 for a file that cannot be read or translated."""
    parser = argparse.ArgumentParser(
        prog="python -m peers.omega_game",
        description="Decide a .slugsin or .structuredslugs spec with omega's GR(1) solver.")
    parser.add_argument("spec", metavar="FILE")
    parser.add_argument("--semantics", choices=SEMANTICS, default=Semantics.DEFAULT)
    args = parser.parse_args(argv)
    try:
        realizable = decide(load_spec_file(args.spec), semantics_named(args.semantics))
    except GaitcError as err:
        print(render_error(err), file=sys.stderr)
        return 1
    print("realizable" if realizable else "unrealizable")
    return 0 if realizable else 3


if __name__ == "__main__":
    sys.exit(main())
