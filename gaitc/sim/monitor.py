"""The run checker: evaluates a spec's assumptions and guarantees on consecutive states of a run.

Independent of the controller that produced the run: it sees only variable valuations.
Safety clauses (init, trans) must hold at every step; liveness clauses (□◇, eqs. 3.7 and
the liveness part of GR(1), Bloem et al. JCSS 2012) are counted, since a finite run cannot
violate them.  Clauses are compiled once to nested Python closures (built by a fold over the
formula, no ``eval``), with results cached per pair of states, so checking costs little per
step; :func:`gaitc.ir.evaluation.evaluate` is the reference semantics the closures agree with.
"""

from __future__ import annotations

import operator
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from gaitc.diagnostics import FormulaError, Span
from gaitc.ir.evaluation import evaluate
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
    Var,
    Xor,
    atoms,
    has_primes,
    node_kind,
    unreachable,
)
from gaitc.ir.spec import SECTIONS, Clause, GR1Spec
from gaitc.ir.traversal import Node, fold, height

Values = tuple[int, ...]
Check = Callable[[Sequence[int]], bool]

_OPS = {"=": "==", "!=": "!=", "<": "<", "<=": "<=", ">": ">", ">=": ">="}


@dataclass(frozen=True)
class Violation:
    """A safety clause that failed at the initial state (step 0) or on the step into ``step``."""

    step: int
    section: str  # env_init, sys_init, env_trans or sys_trans
    index: int  # position of the clause in its section
    rule: str
    span: Span | None

    @property
    def is_assumption(self) -> bool:
        return self.section.startswith("env")

    def describe(self) -> str:
        kind = "assumption" if self.is_assumption else "guarantee"
        where = f" ({self.span})" if self.span is not None else ""
        return f"step {self.step}: {kind} violated: {self.rule}{where}"


def clause_rule(clause: Clause, section: str, index: int) -> str:
    """The human-readable name of a clause: its origin's rule, or its section and index."""
    if clause.origin is not None and clause.origin.rule:
        return clause.origin.rule
    return f"{section}[{index}]"


Fn = Callable[[Sequence[int]], Any]  # a compiled term or formula: its value on ``v``

#: Formulas deeper than this are evaluated by :func:`gaitc.ir.evaluation.evaluate` (iterative)
#: instead: a compiled closure calls one Python frame per level.
MAX_COMPILED_DEPTH = 200

_COMPARE: Mapping[str, Callable[[int, int], bool]] = {
    "=": operator.eq, "!=": operator.ne, "<": operator.lt, "<=": operator.le,
    ">": operator.gt, ">=": operator.ge,
}


class _Compiler:
    """Turns a formula into nested closures over a tuple ``v`` of current+next values (no
    source text and no ``eval``: a fold builds each closure from its operands' closures)."""

    def __init__(self, index: Mapping[str, int], width: int) -> None:
        self.index = index
        self.width = width

    def slot(self, name: str, primed: bool) -> int:
        if name not in self.index:
            raise FormulaError(f"clause mentions '{name}', which the spec does not declare")
        return self.index[name] + (self.width if primed else 0)

    def closure(self, e: Expr) -> Fn:
        fn: Fn = fold(e, self._build, _operands)
        return fn

    def _build(self, node: Node, parts: list[Fn]) -> Fn:
        kind = node_kind(node)
        match kind:
            case Const() | IntConst():
                value = kind.value
                return lambda v: value
            case Var():
                i = self.slot(kind.name, kind.primed)
                return lambda v: v[i] != 0
            case IntVar():
                j = self.slot(kind.name, kind.primed)
                return lambda v: v[j]
            case Not():
                (a,) = parts
                return lambda v: not a(v)
            case And() | Or():
                return _junction(parts, isinstance(kind, And))
            case Add() | Xor() | Iff() | Implies() | Compare():
                return _binary(kind, parts[0], parts[1])
            case Next() | Always() | Eventually():
                raise TypeError(f"cannot compile {type(kind).__name__}")
            case _:
                unreachable(kind)


def _binary(kind: Add | Xor | Iff | Implies | Compare, a: Fn, b: Fn) -> Fn:
    match kind:
        case Add():
            return lambda v: a(v) + b(v)
        case Xor():
            return lambda v: a(v) != b(v)
        case Iff():
            return lambda v: a(v) == b(v)
        case Implies():
            return lambda v: not a(v) or b(v)
        case Compare():
            compare = _COMPARE[kind.op]
            return lambda v: compare(a(v), b(v))
        case _:
            unreachable(kind)


def _junction(parts: Sequence[Fn], conjunction: bool) -> Fn:
    """``and`` (``conjunction``) or ``or`` over ``parts``; the empty conjunction holds and
    the empty disjunction does not."""
    if not parts:
        return lambda v: conjunction
    if len(parts) == 1:
        (a,) = parts
        return lambda v: bool(a(v))
    if len(parts) == 2:
        a, b = parts
        if conjunction:
            return lambda v: bool(a(v)) and bool(b(v))
        return lambda v: bool(a(v)) or bool(b(v))
    items = tuple(parts)
    if conjunction:
        return lambda v: all(p(v) for p in items)
    return lambda v: any(p(v) for p in items)


def _operands(node: Node) -> Sequence[Node]:
    """What :class:`_Compiler` builds into ``node``: operands of operators and sums."""
    if isinstance(node, (Not, And, Or, Xor, Iff, Implies, Compare, Add)):
        return node.children()
    return ()


def compile_formula(expr: Expr, variables: Sequence[str]) -> Check:
    """A closure deciding ``expr`` on ``current + next`` values laid out as ``variables`` twice.

    Agrees with :func:`gaitc.ir.evaluation.evaluate`, which it falls back to for formulas deeper
    than :data:`MAX_COMPILED_DEPTH`.
    """
    index = {name: i for i, name in enumerate(variables)}
    width = len(variables)
    compiler = _Compiler(index, width)
    if height(expr) <= MAX_COMPILED_DEPTH:
        fn = compiler.closure(expr)
        return lambda v: bool(fn(v))
    for name, primed in atoms(expr):
        compiler.slot(name, primed)  # an undeclared name fails here, as when compiled
    names = list(variables)

    def slow(v: Sequence[int]) -> bool:
        valuation = {name: v[i] for i, name in enumerate(names)}
        valuation.update({name + "'": v[width + i] for i, name in enumerate(names)})
        return evaluate(expr, valuation)

    return slow


@dataclass(frozen=True)
class StepCheck:
    """What held on one step: failed safety clauses and satisfied liveness clauses (indices)."""

    env_failed: tuple[int, ...]
    sys_failed: tuple[int, ...]
    env_live: tuple[int, ...]
    sys_live: tuple[int, ...]


class Monitor:
    """Checks valuations against a :class:`GR1Spec`; values are tuples in ``variables`` order."""

    def __init__(self, spec: GR1Spec) -> None:
        self.spec = spec
        self.variables: tuple[str, ...] = tuple(v.name for v in spec.variables())
        self.inputs: tuple[str, ...] = tuple(v.name for v in spec.inputs)
        self._compiled: dict[str, tuple[Check, ...]] = {}
        for section in SECTIONS:
            clauses = spec.section(section)
            self._compiled[section] = tuple(
                compile_formula(c.formula, self.variables) for c in clauses
            )
        self._step_cache: dict[tuple[Values, Values], StepCheck] = {}
        self._primed = {section: tuple(has_primes(c.formula) for c in spec.section(section))
                        for section in ("env_liveness", "sys_liveness")}

    def values(self, valuation: Mapping[str, int]) -> Values:
        """Lay out a name → value mapping in the monitor's variable order (missing: 0)."""
        return tuple(int(valuation.get(name, 0)) for name in self.variables)

    def rule(self, section: str, index: int) -> str:
        return clause_rule(self.spec.section(section)[index], section, index)

    def violation(self, step: int, section: str, index: int) -> Violation:
        clause = self.spec.section(section)[index]
        span = clause.origin.span if clause.origin is not None else None
        return Violation(step, section, index, clause_rule(clause, section, index), span)

    def check_initial(self, state: Values) -> list[Violation]:
        """Violated ``env_init`` and ``sys_init`` clauses of the first state."""
        doubled = state + state
        out = []
        for section in ("env_init", "sys_init"):
            for i, fn in enumerate(self._compiled[section]):
                if not fn(doubled):
                    out.append(self.violation(0, section, i))
        return out

    def check_step(self, current: Values, nxt: Values) -> StepCheck:
        """Evaluate the transition and liveness clauses on the pair ``(current, nxt)``."""
        key = (current, nxt)
        found = self._step_cache.get(key)
        if found is not None:
            return found
        pair = current + nxt
        c = self._compiled
        result = StepCheck(
            tuple(i for i, fn in enumerate(c["env_trans"]) if not fn(pair)),
            tuple(i for i, fn in enumerate(c["sys_trans"]) if not fn(pair)),
            tuple(i for i, fn in enumerate(c["env_liveness"]) if fn(pair)),
            tuple(i for i, fn in enumerate(c["sys_liveness"]) if fn(pair)),
        )
        self._step_cache[key] = result
        return result

    def liveness_at(self, previous: Values | None, state: Values
                    ) -> tuple[tuple[int, ...], tuple[int, ...]]:
        """The □◇ assumptions and guarantees that hold at ``state`` (indices).

        The one reading of "held on a step" that the run summary uses everywhere: a clause
        without next-state variables holds at a state when it is true there; a clause with
        them holds at a state when it is true on the move into it (at the first state, on
        the state itself), as the goals of :meth:`gaitc.sim.domain.Domain.goals_reached`.
        """
        before = state if previous is None else previous
        moved, still = before + state, state + state

        def holding(section: str) -> tuple[int, ...]:
            primed = self._primed[section]
            return tuple(i for i, fn in enumerate(self._compiled[section])
                         if fn(moved if primed[i] else still))

        return holding("env_liveness"), holding("sys_liveness")

    def failed_assumptions(self, current: Values, nxt_inputs: Mapping[str, int]) -> list[int]:
        """Indices of ``env_trans`` clauses that forbid the environment's next ``nxt_inputs``.

        Outputs of the next state are unknown at this point; clauses that mention them are
        checked with every output unchanged, the weakest reading for the environment.
        """
        width = len(self.variables)
        nxt = [current[i] for i in range(width)]
        for i, name in enumerate(self.variables):
            if name in nxt_inputs:
                nxt[i] = int(nxt_inputs[name])
        pair = current + tuple(nxt)
        return [i for i, fn in enumerate(self._compiled["env_trans"]) if not fn(pair)]

