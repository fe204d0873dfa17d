"""The canonical choices of an explicit extraction, shared by the strategy and the
counter-strategy extractors and the explanation's play.

Every choice among several assignments takes the smallest in the static variable order,
whatever order CUDD has sifted the BDDs into, so that the same spec gives the same controller
byte for byte (:attr:`~gaitc.solver.symbolic.SymbolicSpec.choice_rank`). Also here: cofactors
by an assignment, the primed names of bits, the spec's integer groups, the initial states of
either semantics, and the bounded memo every extraction keeps.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import Final, TypeVar

from gaitc.ir.bddwalk import State, all_assignments, cofactor, first_assignment
from gaitc.ir.controller import IntegerVar, integers_of
from gaitc.ir.spec import Semantics
from gaitc.solver.symbolic import BDDNode, SymbolicSpec

#: An extraction tells its progress every this many nodes.
REPORT_EVERY: Final = 1000
#: The most choices whose smallest move (or input sets whose assignments) an extraction
#: remembers at once.
REMEMBERED: Final = 100_000
T = TypeVar("T")


def assignments(sym: SymbolicSpec, u: BDDNode, bits: Sequence[str]) -> list[State]:
    """Every assignment to ``bits`` (a superset of ``u``'s support), sorted."""
    return all_assignments(sym.bdd, u, bits)


def smallest(sym: SymbolicSpec, u: BDDNode, bits: Sequence[str]) -> State | None:
    """The smallest assignment to ``bits`` inside ``u`` (None if empty), bits compared in
    the static order whatever the current BDD order (:attr:`SymbolicSpec.choice_rank`)."""
    return first_assignment(sym.bdd, u, bits, sym.choice_rank)


def fix(sym: SymbolicSpec, u: BDDNode, bits: Sequence[str], values: Iterable[int]) -> BDDNode:
    """``u`` with ``bits`` set to ``values`` (a cofactor)."""
    return cofactor(sym.bdd, {b: bool(v) for b, v in zip(bits, values, strict=True)}, u)


def primed(bits: Sequence[str]) -> list[str]:
    return [b + "'" for b in bits]


def spec_integers(sym: SymbolicSpec) -> dict[str, IntegerVar]:
    """Integer variables of the spec, plus SLUGS-encoded bit groups among Boolean names."""
    names = sym.input_bits + sym.output_bits
    found = integers_of(names, frozenset(sym.input_bits))
    for v in sym.spec.variables():
        if v.is_integer and v.low is not None and v.high is not None:
            owner = "env" if v in sym.spec.inputs else "sys"
            found[v.name] = IntegerVar(v.low, v.high, tuple(sym.var_bits[v.name]), owner)
    return found


def initial_states(sym: SymbolicSpec, winning: BDDNode, semantics: Semantics) -> list[State]:
    """Initial states: one per θe-allowed input (default) or all of θe ∧ θs (robotics)."""
    ins, outs = list(sym.input_bits), list(sym.output_bits)
    if semantics == Semantics.ROBOTICS:
        return assignments(sym, sym.env_init & sym.sys_init & winning, ins + outs)
    out = []
    for x in assignments(sym, sym.bdd.exist(sym.pre_outputs, sym.env_init), ins):
        y = smallest(sym, fix(sym, sym.sys_init & winning, ins, x), outs)
        if y is not None:
            out.append(x + y)
    return out


def remembered(compute: Callable[[BDDNode], T]) -> Callable[[BDDNode], T]:
    """``compute`` with its answers kept by argument, at most :data:`REMEMBERED` at once
    (then the memory starts again)."""
    known: dict[BDDNode, T] = {}

    def answer(u: BDDNode) -> T:
        if u in known:
            return known[u]
        if len(known) >= REMEMBERED:
            known.clear()
        found = known[u] = compute(u)
        return found

    return answer
