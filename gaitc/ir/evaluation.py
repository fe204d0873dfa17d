"""Evaluating formulas of the IR on concrete valuations (simulation, checks, tests).

A fold over the DAG (:mod:`gaitc.ir.traversal`): each shared node is evaluated once and deep
formulas need no recursion.  ``Next``/``Always``/``Eventually`` cannot be evaluated on one
step and raise :class:`~gaitc.diagnostics.FormulaError`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from gaitc.diagnostics import FormulaError
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
    Node,
    Not,
    Or,
    Term,
    Var,
    Xor,
    node_kind,
    unreachable,
)
from gaitc.ir.traversal import fold

Valuation = Mapping[str, int]


def _key(name: str, primed: bool) -> str:
    return name + "'" if primed else name


def _value(node: Node, args: list[Any], valuation: Valuation) -> Any:
    kind = node_kind(node)
    match kind:
        case Const() | IntConst():
            return kind.value
        case Var():
            return bool(valuation[_key(kind.name, kind.primed)])
        case IntVar():
            return int(valuation[_key(kind.name, kind.primed)])
        case Add():
            return args[0] + args[1]
        case Not():
            return not args[0]
        case And():
            return all(args)
        case Or():
            return any(args)
        case Xor():
            return args[0] != args[1]
        case Iff():
            return args[0] == args[1]
        case Implies():
            return (not args[0]) or args[1]
        case Compare():
            a, b = args
            return {
                "=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b
            }[kind.op]
        case Next() | Always() | Eventually():
            raise FormulaError(f"cannot evaluate temporal operator {type(kind).__name__}",
                               kind.span)
        case _:
            unreachable(kind)


def _evaluate_node(root: Node, valuation: Valuation) -> Any:
    """Bottom-up evaluation (:func:`~gaitc.ir.traversal.fold`); each shared node once."""
    return fold(root, lambda node, args: _value(node, args, valuation))


def evaluate_term(term: Term, valuation: Valuation) -> int:
    """Value of an integer term; primed variables are looked up as ``name'``."""
    return int(_evaluate_node(term, valuation))


def evaluate(expr: Expr, valuation: Valuation) -> bool:
    """Truth value of a next-free formula; ``valuation`` maps ``x`` and ``x'`` to 0/1 or ints."""
    return bool(_evaluate_node(expr, valuation))
