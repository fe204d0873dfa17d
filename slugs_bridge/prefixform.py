"""What the slugsin format keeps of a formula: the IR its writer and reader give back.

slugsin has only ``! & | ^``, so :func:`~slugs_bridge.slugsin.emit_formula` spells
``a <-> b`` as ``! ^ a b`` and ``a -> b`` as ``| ! a b``, and the reader flattens the
``|`` chains that spelling creates into the disjunctions around them.  :func:`prefix_form`
computes that result from the formula itself (not through text), so the round trip
``parse_slugsin(emit_slugsin(spec)) == prefix_spec(spec)`` states exactly what is lost.
"""

from __future__ import annotations

from dataclasses import replace

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
    Node,
    Not,
    Or,
    Var,
    Xor,
    formula_kind,
    unreachable,
)
from gaitc.ir.spec import SECTIONS, GR1Spec
from slugs_bridge.slugsin import _buffered_nodes, intern_formula

_Plan = list[tuple[bool, Expr]]  # (negated, operand) pieces of a chain, or the children


def _chain_op(node: Node) -> str | None:
    if isinstance(node, Implies):
        return "|"
    if isinstance(node, (And, Or)) and len(node.args) >= 2:
        return "&" if isinstance(node, And) else "|"
    return None


def _operands(node: Expr) -> _Plan:
    if isinstance(node, Implies):
        return [(True, node.left), (False, node.right)]
    assert isinstance(node, (And, Or))
    return [(False, arg) for arg in node.args]


def _chain(node: Expr, buffered: set[int]) -> _Plan:
    """The operands the reader collects into ``node``'s chain: written inline, operands
    with the same chain operator join it, unless they went through the ``$`` buffer."""
    op = _chain_op(node)
    out: _Plan = []
    stack = list(reversed(_operands(node)))
    while stack:
        negated, item = stack.pop()
        if negated or id(item) in buffered:
            out.append((negated, item))
        elif isinstance(item, (And, Or)) and len(item.args) == 1:
            stack.append((False, item.args[0]))  # written as its operand
        elif _chain_op(item) == op:
            stack.extend(reversed(_operands(item)))
        else:
            out.append((False, item))
    return out


def _plan(node: Expr, buffered: set[int]) -> _Plan:
    if _chain_op(node) is not None:
        return _chain(node, buffered)
    kind = formula_kind(node)
    match kind:
        case Not():
            return [(False, kind.arg)]
        case Xor() | Iff():
            return [(False, kind.left), (False, kind.right)]
        case And() | Or():
            return [(False, arg) for arg in kind.args]  # at most one
        case Var() | Const():
            return []
        case Implies():  # always a chain (_chain_op)
            return [(True, kind.left), (False, kind.right)]
        case Compare() | Next() | Always() | Eventually():
            raise ValueError(f"cannot write {type(kind).__name__} in slugsin: the format is "
                             "Boolean and next-free")
        case _:
            unreachable(kind)


def _build(node: Expr, plan: _Plan, done: dict[int, Expr]) -> Expr:
    parts = [Not(done[id(item)]) if negated else done[id(item)] for negated, item in plan]
    op = _chain_op(node)
    if op is not None:
        return (And if op == "&" else Or)(tuple(parts), span=node.span)
    if isinstance(node, Not):
        return Not(parts[0], span=node.span)
    if isinstance(node, Xor):
        return Xor(parts[0], parts[1], span=node.span)
    if isinstance(node, Iff):
        return Not(Xor(parts[0], parts[1], span=node.span), span=node.span)
    if isinstance(node, (And, Or)):
        return parts[0] if parts else Const(isinstance(node, And), span=node.span)
    return node


def prefix_form(expr: Expr) -> Expr:
    """The formula ``parse_prefix(emit_formula(expr))`` gives back, computed directly.

    ``<->`` becomes ``!(^)``, ``->`` becomes ``|`` with a negated left operand (flattened
    into an enclosing ``|`` chain, and taking in a ``|`` or ``->`` on its right, when
    written inline), ``&``/``|`` of fewer than two operands become ``1``/``0`` or the
    operand.  Shared nodes stay shared, and equal subformulas are one node, as the reader
    makes them on a line (:func:`~slugs_bridge.slugsin.intern_formula`); no recursion, so
    any depth is fine.
    """
    buffered = {id(n) for n in _buffered_nodes(expr)}
    done: dict[int, Expr] = {}
    stack: list[tuple[Expr, _Plan | None]] = [(expr, None)]
    while stack:
        node, plan = stack.pop()
        if id(node) in done:
            continue
        if plan is None:
            plan = _plan(node, buffered)
            missing = [item for _, item in plan if id(item) not in done]
            if missing:
                stack.append((node, plan))
                stack.extend((item, None) for item in missing)
                continue
        done[id(node)] = _build(node, plan, done)
    return intern_formula(done[id(expr)])


def prefix_spec(spec: GR1Spec) -> GR1Spec:
    """``spec`` with every clause in :func:`prefix_form`: what ``parse_slugsin`` reads back
    from ``emit_slugsin(spec)`` (``spec`` must be Boolean; bit-blast it first)."""
    return spec.with_sections(**{
        name: tuple(replace(c, formula=prefix_form(c.formula)) for c in spec.section(name))
        for name in SECTIONS
    })
