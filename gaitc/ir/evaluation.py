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
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Node,
    Not,
    Or,
    Term,
    Var,
    Xor,
)
from gaitc.ir.traversal import fold

Valuation = Mapping[str, int]


def _key(name: str, primed: bool) -> str:
    return name + "'" if primed else name


def _value(node: Node, args: list[Any], valuation: Valuation) -> Any:
    if isinstance(node, (Const, IntConst)):
        return node.value
    if isinstance(node, (Var, IntVar)):
        value = valuation[_key(node.name, node.primed)]
        return bool(value) if isinstance(node, Var) else int(value)
    if isinstance(node, Add):
        return args[0] + args[1]
    if isinstance(node, Not):
        return not args[0]
    if isinstance(node, And):
        return all(args)
    if isinstance(node, Or):
        return any(args)
    if isinstance(node, Xor):
        return args[0] != args[1]
    if isinstance(node, Iff):
        return args[0] == args[1]
    if isinstance(node, Implies):
        return (not args[0]) or args[1]
    if isinstance(node, Compare):
        a, b = args
        return {
            "=": a == b, "!=": a != b, "<": a < b, "<=": a <= b, ">": a > b, ">=": a >= b
        }[node.op]
    raise FormulaError(f"cannot evaluate temporal operator {type(node).__name__}", node.span)


def _evaluate_node(root: Node, valuation: Valuation) -> Any:
    """Bottom-up evaluation (:func:`~gaitc.ir.traversal.fold`); each shared node once."""
    return fold(root, lambda node, args: _value(node, args, valuation))


def evaluate_term(term: Term, valuation: Valuation) -> int:
    """Value of an integer term; primed variables are looked up as ``name'``."""
    return int(_evaluate_node(term, valuation))


def evaluate(expr: Expr, valuation: Valuation) -> bool:
    """Truth value of a next-free formula; ``valuation`` maps ``x`` and ``x'`` to 0/1 or ints."""
    return bool(_evaluate_node(expr, valuation))
