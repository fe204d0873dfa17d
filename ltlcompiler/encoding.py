"""Variable naming and the two encodings of robot state as GR(1) variables: ``onehot``
(the thesis, section 3.3: a proposition per region, gait, health level p_{i,j} and hazard)
and ``binary`` (an integer per quantity).  See :class:`OneHot` and :class:`Binary`."""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Final

from gaitc.diagnostics import FormulaError, SpecSemanticError, UsageError
from gaitc.diagnostics.choices import Choice
from gaitc.ir.evaluation import evaluate
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Not,
    Or,
    Var,
    Xor,
    conj,
    disj,
    walk,
)
from gaitc.ir.spec import Variable
from gaitc.ir.traversal import Node, rebuild

if TYPE_CHECKING:  # only named in annotations: a .slugsin spec never loads the model
    from ltlcompiler.model import Model


class EncodingName(Choice):
    """How a ``.gait`` model becomes variables: ``onehot``, the thesis's proposition per
    region, gait and health level; ``binary``, integer variables, bit-blasted as SLUGS's
    converter does."""

    ONEHOT = "onehot"
    BINARY = "binary"


ENCODINGS: Final = tuple(EncodingName)
REGION_VAR = "region"
GAIT_VAR = "gait"
HAZARD_VAR = "hazard"


def health_prop(leg: str, level: int) -> str:
    """The onehot name of p_{leg,level}."""
    return f"{leg}_h{level}"


def at_most_one(items: Sequence[Expr]) -> Expr:
    """No two of ``items`` hold; O(n log n) size by halving (no pairwise blow-up)."""
    if len(items) <= 1:
        return Const(True)
    if len(items) == 2:
        return Not(conj(items))
    half = len(items) // 2
    left, right = items[:half], items[half:]
    parts = [at_most_one(left), at_most_one(right), Not(conj((disj(left), disj(right))))]
    return conj(p for p in parts if not isinstance(p, Const))


def exactly_one(items: Sequence[Expr]) -> Expr:
    """Exactly one of ``items`` holds."""
    return conj((disj(items), at_most_one(items))) if len(items) > 1 else disj(items)


class Encoding:
    """How the objects of one model appear as spec variables; subclasses per encoding."""

    name = ""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.region_index = {r.name: i for i, r in enumerate(model.regions)}
        self.gait_index = {g.name: i for i, g in enumerate(model.gaits)}
        self.hazard_index = {h.name: i + 1 for i, h in enumerate(model.hazards)}
        self.legs = {leg.name: leg for leg in model.legs}

    # ------------------------------------------------------------ variables
    def inputs(self) -> tuple[Variable, ...]:
        raise NotImplementedError

    def outputs(self) -> tuple[Variable, ...]:
        raise NotImplementedError

    def output_names(self) -> frozenset[str]:
        return frozenset(v.name for v in self.outputs())

    # ------------------------------------------------------------ atoms
    def region(self, name: str, primed: bool = False) -> Expr:
        raise NotImplementedError

    def gait(self, name: str, primed: bool = False) -> Expr:
        raise NotImplementedError

    def hazard(self, name: str, primed: bool = False) -> Expr:
        raise NotImplementedError

    def health(self, leg: str, level: int, primed: bool = False) -> Expr:
        """Leg ``leg`` is at health level ``level``."""
        raise NotImplementedError

    def keep_health(self, leg: str) -> Expr:
        """φ_{D_k}: the leg's health does not change this step."""
        raise NotImplementedError

    def degrade_health(self, leg: str) -> Expr:
        """φ_{D_i}: the leg keeps its level or drops by one (level 1 stays)."""
        levels = self.legs[leg].health
        parts: list[Expr] = [
            Implies(self.health(leg, j), disj((self.health(leg, j, True),
                                                self.health(leg, j - 1, True))))
            for j in range(levels, 1, -1)
        ]
        parts.append(Implies(self.health(leg, 1), self.health(leg, 1, True)))
        return conj(parts)

    def wear_health(self, leg: str, levels: int) -> Expr:
        """The leg keeps its level or loses up to ``levels`` levels, never below level 1
        (a graded hazard, eq. 3.5 generalised): health' in [max(1, health - levels), health].
        For ``levels`` 1 this is :meth:`degrade_health` itself, clause for clause."""
        if levels < 1:
            raise ValueError(f"a leg wears at least 1 level a step, not {levels}")
        if levels == 1:
            return self.degrade_health(leg)
        return conj(Implies(self.health(leg, j), disj(self.health(leg, i, True)
                                                       for i in range(j, max(1, j - levels) - 1,
                                                                      -1)))
                    for j in range(self.legs[leg].health, 0, -1))

    # ------------------------------------------------------------ mutual exclusion
    def mutex(self, primed: bool) -> Iterator[tuple[str, str, Expr]]:
        """``(section kind, rule, formula)``: the exclusions the thesis omits (onehot only)."""
        return iter(())

    # ------------------------------------------------------------ user formulas
    def translate(self, expr: Expr) -> Expr:
        """Rewrite a next-free user formula's atoms (model namespace) into this encoding."""
        return rebuild(expr, self._replace)

    def _replace(self, node: Node) -> Node | None:
        """The encoding of an atom; None (rebuild with translated operands) for an operator."""
        if isinstance(node, Var):
            return self._atom(node)
        if isinstance(node, Compare):
            return self._compare(node)
        if isinstance(node, (Const, Not, And, Or, Xor, Iff, Implies)):
            return None
        raise FormulaError(f"temporal operator {type(node).__name__} is not allowed here: "
                           "GR(1) allows it only at the top of an assumption or guarantee",
                           node.span)

    def _atom(self, var: Var) -> Expr:
        if var.name in self.region_index:
            return self.region(var.name, var.primed)
        if var.name in self.gait_index:
            return self.gait(var.name, var.primed)
        if var.name in self.hazard_index:
            return self.hazard(var.name, var.primed)
        if var.name in self.legs:
            raise FormulaError(
                f"leg '{var.name}' is a health level, not a proposition; compare it, "
                f"e.g. 'health({var.name}) > 1'", var.span)
        raise FormulaError(f"unknown name '{var.name}' in formula: use a region, gait, "
                           "hazard or a comparison on a leg's health", var.span)

    def _compare(self, cmp: Compare) -> Expr:
        names = sorted({(n.name, n.primed) for n in walk(cmp) if isinstance(n, IntVar)})
        for name, _ in names:
            if name not in self.legs:
                raise FormulaError(f"'{name}' is not a leg: only a leg's health level is an "
                                   "integer in a formula", cmp.span)
        return self._compare_legs(cmp, names)

    def _compare_legs(self, cmp: Compare, names: list[tuple[str, bool]]) -> Expr:
        raise NotImplementedError


class OneHot(Encoding):
    """The thesis encoding: one Boolean per region, gait, health level and hazard.

    Region, gait and hazard propositions keep the object's own name; the health
    proposition p_{i,j} of leg ``L`` at level ``j`` is ``L_h<j>`` (e.g. ``L3_h2``).
    :func:`check_names` rejects a model whose own names collide with these.
    """

    name = "onehot"

    def inputs(self) -> tuple[Variable, ...]:
        health = [Variable(health_prop(leg.name, j), span=leg.span)
                  for leg in self.model.legs for j in range(leg.health, 0, -1)]
        hazards = [Variable(h.name, span=h.span) for h in self.model.hazards]
        return tuple(health + hazards)

    def outputs(self) -> tuple[Variable, ...]:
        return tuple([Variable(r.name, span=r.span) for r in self.model.regions]
                     + [Variable(g.name, span=g.span) for g in self.model.gaits])

    def region(self, name: str, primed: bool = False) -> Expr:
        return Var(name, primed)

    def gait(self, name: str, primed: bool = False) -> Expr:
        return Var(name, primed)

    def hazard(self, name: str, primed: bool = False) -> Expr:
        return Var(name, primed)

    def health(self, leg: str, level: int, primed: bool = False) -> Expr:
        return Var(health_prop(leg, level), primed)

    def keep_health(self, leg: str) -> Expr:
        return conj(Iff(self.health(leg, j), self.health(leg, j, True))
                    for j in range(self.legs[leg].health, 0, -1))

    def mutex(self, primed: bool) -> Iterator[tuple[str, str, Expr]]:
        m = self.model
        yield "sys", "mutex: exactly one region", exactly_one(
            [self.region(r.name, primed) for r in m.regions])
        yield "sys", "mutex: exactly one gait", exactly_one(
            [self.gait(g.name, primed) for g in m.gaits])
        for leg in m.legs:
            yield "env", f"mutex: leg {leg.name} has exactly one health level", exactly_one(
                [self.health(leg.name, j, primed) for j in range(leg.health, 0, -1)])
        if len(m.hazards) > 1:
            yield "env", "mutex: at most one hazard set is active", at_most_one(
                [self.hazard(h.name, primed) for h in m.hazards])

    def _compare_legs(self, cmp: Compare, names: list[tuple[str, bool]]) -> Expr:
        ranges = [range(self.legs[n].health, 0, -1) for n, _ in names]
        cases: list[Expr] = []
        for levels in itertools.product(*ranges):
            valuation = {(n + "'" if p else n): v for (n, p), v in zip(names, levels, strict=True)}
            if evaluate(cmp, valuation):
                cases.append(conj(self.health(n, v, p)
                                  for (n, p), v in zip(names, levels, strict=True)))
        if not cases:
            return Const(False, span=cmp.span)
        if len(cases) == len(list(itertools.product(*ranges))):
            return Const(True, span=cmp.span)
        return disj(cases, span=cmp.span)


class Binary(Encoding):
    """Integer variables: outputs ``region`` (0..p-1) and ``gait`` (0..m-1) index the
    declaration order (noGait last); inputs ``<leg>`` (1..h) hold a leg's health level and
    ``hazard`` (0..ν) the active hazard set, 0 meaning none, sets numbered from 1 in
    declaration order (omitted when there are no hazards).  Ranges make every mutual
    exclusion implicit."""

    name = "binary"

    def inputs(self) -> tuple[Variable, ...]:
        out = [Variable(leg.name, 1, leg.health, span=leg.span) for leg in self.model.legs]
        if self.model.hazards:
            out.append(Variable(HAZARD_VAR, 0, len(self.model.hazards)))
        return tuple(out)

    def outputs(self) -> tuple[Variable, ...]:
        return (Variable(REGION_VAR, 0, len(self.model.regions) - 1),
                Variable(GAIT_VAR, 0, len(self.model.gaits) - 1))

    @staticmethod
    def _eq(var: str, value: int, primed: bool) -> Expr:
        return Compare("=", IntVar(var, primed), IntConst(value))

    def region(self, name: str, primed: bool = False) -> Expr:
        return self._eq(REGION_VAR, self.region_index[name], primed)

    def gait(self, name: str, primed: bool = False) -> Expr:
        return self._eq(GAIT_VAR, self.gait_index[name], primed)

    def hazard(self, name: str, primed: bool = False) -> Expr:
        return self._eq(HAZARD_VAR, self.hazard_index[name], primed)

    def health(self, leg: str, level: int, primed: bool = False) -> Expr:
        return self._eq(leg, level, primed)

    def keep_health(self, leg: str) -> Expr:
        return Compare("=", IntVar(leg, True), IntVar(leg))

    def degrade_health(self, leg: str) -> Expr:
        drops = [conj((self.health(leg, j), self.health(leg, j - 1, True)))
                 for j in range(self.legs[leg].health, 1, -1)]
        return disj([self.keep_health(leg), *drops])

    def wear_health(self, leg: str, levels: int) -> Expr:
        """health' <= health & health' + levels >= health: two comparisons whatever the
        number of levels (the range 1..h keeps the leg above 0); for one level, eq. 3.5's
        :meth:`degrade_health` as it is."""
        if levels < 1:
            raise ValueError(f"a leg wears at least 1 level a step, not {levels}")
        if levels == 1:
            return self.degrade_health(leg)
        now, after = IntVar(leg), IntVar(leg, True)
        if levels >= self.legs[leg].health - 1:  # any level from here down to failed
            return Compare("<=", after, now)
        return conj((Compare("<=", after, now),
                     Compare(">=", Add(after, IntConst(levels)), now)))

    def _compare_legs(self, cmp: Compare, names: list[tuple[str, bool]]) -> Expr:
        return cmp


def make_encoding(model: Model, encoding: EncodingName) -> Encoding:
    """The :class:`Encoding` named ``encoding`` ("onehot" or "binary") for ``model``."""
    if encoding == EncodingName.ONEHOT:
        return OneHot(model)
    if encoding == EncodingName.BINARY:
        return Binary(model)
    raise UsageError(f"unknown encoding '{encoding}': use one of {', '.join(ENCODINGS)}")


def check_names(model: Model, encoding: EncodingName) -> None:
    """Raise :class:`SpecSemanticError` when a user name collides with a generated name."""
    enc = make_encoding(model, encoding)
    seen: dict[str, Variable] = {}
    for var in enc.inputs() + enc.outputs():
        first = seen.setdefault(var.name, var)
        if first is not var:
            raise SpecSemanticError(
                f"the name '{var.name}' clashes with a variable that gaitc generates in the "
                f"{encoding} encoding; rename it",
                var.span or first.span,
                hint="leg L's health levels are named L_h1, L_h2, ... (onehot); "
                "'region', 'gait' and 'hazard' are reserved (binary)",
            )
