"""Shapes of formula DAGs for the readers and writers, computed without recursion.

:func:`primed` (a formula one step later, for the infix reader's ``next``),
:func:`tree_size` (how large a DAG grows when written as a tree) and
:func:`prefix_exact` (whether slugsin's operators spell a formula node for node).
"""

from __future__ import annotations

from typing import cast

from gaitc.diagnostics import SlugsFormatError, Span
from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Expr,
    Iff,
    Implies,
    IntVar,
    Node,
    Not,
    Or,
    Term,
    Var,
    Xor,
    walk,
)


def _post_order(root: Node) -> list[Node]:
    """Every node of ``root`` once, children before parents."""
    out: list[Node] = []
    seen: set[int] = set()
    stack: list[tuple[Node, bool]] = [(root, False)]
    while stack:
        node, ready = stack.pop()
        if ready:
            out.append(node)
            continue
        if id(node) in seen:
            continue
        seen.add(id(node))
        stack.append((node, True))
        stack.extend((kid, False) for kid in reversed(node.children()) if id(kid) not in seen)
    return out


def primed(root: Node) -> Node:
    """``root`` with every variable primed (shared nodes stay shared)."""
    done: dict[int, Node] = {}
    for node in _post_order(root):
        done[id(node)] = _rebuilt(node, [done[id(kid)] for kid in node.children()])
    return done[id(root)]


def _rebuilt(node: Node, kids: list[Node]) -> Node:
    span = node.span
    if isinstance(node, (Var, IntVar)):
        return type(node)(node.name, True, span=span)
    if isinstance(node, Not):
        return Not(cast(Expr, kids[0]), span=span)
    if isinstance(node, (And, Or)):
        return type(node)(tuple(cast(list[Expr], kids)), span=span)
    if isinstance(node, (Xor, Iff, Implies)):
        return type(node)(cast(Expr, kids[0]), cast(Expr, kids[1]), span=span)
    if isinstance(node, Compare):
        return Compare(node.op, cast(Term, kids[0]), cast(Term, kids[1]), span=span)
    if isinstance(node, Add):
        return Add(cast(Term, kids[0]), cast(Term, kids[1]), span=span)
    return node


def tree_size(root: Node, limit: int) -> int:
    """Nodes of ``root`` written as a tree (shared nodes counted each time), capped at
    ``limit + 1``: a DAG of n nodes can stand for a tree of 2**n."""
    size: dict[int, int] = {}
    for node in _post_order(root):
        size[id(node)] = min(limit + 1, 1 + sum(size[id(kid)] for kid in node.children()))
    return size[id(root)]


def prefix_exact(expr: Expr) -> bool:
    """Whether slugsin spells ``expr`` node for node: no ``<->``/``->`` (written with
    ``! ^ |``) and no ``&``/``|`` of fewer than two operands (written as a constant or the
    operand itself)."""
    return not any(
        isinstance(n, (Iff, Implies)) or (isinstance(n, (And, Or)) and len(n.args) < 2)
        for n in walk(expr)
    )


MAX_DIGITS = 18  # integer constants and range ends; no BDD could hold a wider range


def checked_int(text: str, span: Span | None) -> int:
    """``text`` (ASCII digits, an optional minus) as an int, at most :data:`MAX_DIGITS`
    digits long; a positioned :class:`SlugsFormatError` otherwise."""
    digits = text.strip().removeprefix("-")
    if not (digits.isascii() and digits.isdigit()):
        raise SlugsFormatError(f"'{text}' is not a whole number", span)
    if len(digits) > MAX_DIGITS:
        raise SlugsFormatError(f"the number has {len(digits)} digits; the limit is "
                               f"{MAX_DIGITS}", span)
    return int(text)
