"""The verifiers' own reading of a spec: its clauses as BDDs over bits and primed bits.

Shared by the explicit checkers (:mod:`gaitc.verifier.strategy`,
:mod:`gaitc.verifier.counterstrategy`) and the symbolic one (:mod:`gaitc.verifier.symbolic`), and
by nothing in the solver: a formula gets a translation here that is independent of
:mod:`gaitc.solver.symbolic`.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from gaitc.diagnostics import FormulaError
from gaitc.ir.formula import (
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Expr,
    Iff,
    Implies,
    Next,
    Not,
    Or,
    Var,
    Xor,
    formula_kind,
    unreachable,
)
from gaitc.ir.manager import manager
from gaitc.ir.spec import Clause, GR1Spec
from gaitc.ir.traversal import Memo, Node, fold

if TYPE_CHECKING:
    from dd.cudd import Function

Bits = tuple[int, ...]


def _rule(section: str, index: int, clause: Clause) -> str:
    origin, span = clause.origin, clause.origin and clause.origin.span
    where = f" '{origin.rule}'" if origin is not None else ""
    return f"{section} clause #{index + 1}{where}" + (f" ({span})" if span else "")


class Logic:
    """BDDs of the spec's clauses over unprimed and primed (``x'``) bits, cached evaluation.

    Every BDD whose id is a cache key passes through :meth:`support`, which keeps it
    referenced, so CUDD cannot reuse the id for another function.
    """

    def __init__(self, spec: GR1Spec, order: Sequence[str] = ()) -> None:
        """``order``: variables to put first in the BDD order (a controller's own order)."""
        self.spec = spec
        self.inputs = tuple(v.name for v in spec.inputs)
        self.outputs = tuple(v.name for v in spec.outputs)
        self.bdd = manager()
        names = {n for b in self.inputs + self.outputs for n in (b, b + "'")}
        listed = [n for n in order if n in names]
        known = set(listed)
        for n in listed:  # a bit the order leaves out goes next to its other copy
            partner = n[:-1] if n.endswith("'") else n + "'"
            self.bdd.declare(n)
            if partner not in known:
                self.bdd.declare(partner)
                known.add(partner)
        for name in self.inputs + self.outputs:
            self.bdd.declare(name, name + "'")
        self._memo: Memo[Function] = {}
        self._lets: dict[tuple[int, Bits], Function] = {}
        self._support: dict[int, tuple[Function, tuple[str, ...]]] = {}
        self._clauses: dict[str, list[tuple[str, Function]]] = {}

    def clauses(self, section: str) -> list[tuple[str, Function]]:
        """``(description, BDD)`` of every clause of ``section``."""
        if section not in self._clauses:
            items = self.spec.section(section)
            self._clauses[section] = [
                (_rule(section, k, c), self.translate(c.formula)) for k, c in enumerate(items)
            ]
        return self._clauses[section]

    def conjunction(self, section: str) -> Function:
        """The BDD of every clause of ``section`` at once (true for an empty section)."""
        out: Function = self.bdd.true
        for _, u in self.clauses(section):
            out &= u
        return out

    def translate(self, expr: Expr) -> Function:
        """The BDD of a Boolean formula (memoised on node identity, so DAGs stay cheap)."""
        return fold(expr, self._translate, lambda n: n.children() if isinstance(
            n, (Not, And, Or, Xor, Iff, Implies)) else (), self._memo)  # others: rejected

    def _translate(self, expr: Node, args: list[Function]) -> Function:
        b = self.bdd
        kind = formula_kind(expr)
        match kind:
            case Const():
                return b.true if kind.value else b.false
            case Var():
                name = kind.name + ("'" if kind.primed else "")
                if name not in b.vars:
                    raise FormulaError(f"'{kind.name}' is not a variable of the specification",
                                       kind.span)
                return b.var(name)
            case Not():
                return ~args[0]
            case And():
                return functools.reduce(lambda x, y: b.apply("and", x, y), args, b.true)
            case Or():
                return functools.reduce(lambda x, y: b.apply("or", x, y), args, b.false)
            case Xor():
                return b.apply("xor", args[0], args[1])
            case Iff():
                return b.apply("equiv", args[0], args[1])
            case Implies():
                return b.apply("implies", args[0], args[1])
            case Compare() | Next() | Always() | Eventually():
                raise FormulaError(f"the verifier cannot check {type(kind).__name__} formulas; "
                                   "bit-blast integers first", kind.span)
            case _:
                unreachable(kind)

    def support(self, u: Function) -> tuple[str, ...]:
        key = int(u)
        if key not in self._support:  # keeps ``u`` alive: its id is a key of the other caches
            self._support[key] = (u, tuple(sorted(self.bdd.support(u))))
        return self._support[key][1]

    def _let(self, u: Function, values: Mapping[str, bool], names: tuple[str, ...]) -> Function:
        key = (int(u), tuple(int(values[n]) for n in names))
        found = self._lets.get(key)
        if found is None:
            found = self._lets[key] = self.bdd.let({n: values[n] for n in names}, u)
        return found

    def holds(self, u: Function, valuation: Mapping[str, bool]) -> bool:
        """Truth of ``u`` under ``valuation`` (must cover its support); cached on the support."""
        names = self.support(u)
        return bool((self._let(u, valuation, names) if names else u) == self.bdd.true)

    def restrict(self, u: Function, current: Mapping[str, bool]) -> Function:
        """``u`` with its unprimed bits fixed to ``current`` (cached on those bits)."""
        key = -int(u)
        if key not in self._support:
            self._support[key] = (u, tuple(n for n in self.support(u) if not n.endswith("'")))
        names = self._support[key][1]
        return self._let(u, current, names) if names else u

    def pick(self, u: Function, names: Sequence[str], primed: bool) -> tuple[dict[str, bool], int]:
        """One assignment of ``u`` to ``names`` (unprimed keys) and how many there are."""
        suffix = "'" if primed else ""
        care = {n + suffix for n in names}
        example = self.bdd.pick(u, care_vars=care) or {}
        chosen = {n: bool(example.get(n + suffix, False)) for n in names}
        return chosen, int(self.bdd.count(u, nvars=len(care)))
