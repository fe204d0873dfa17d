"""Writer of infix formulas: structuredslugs lines and the bodies of the readable LTL text.

The fewest brackets that keep a formula's shape under SLUGS's grammar (see
:mod:`slugs_bridge.infix`), written from an explicit stack, so formulas nested any number
of levels deep are fine.  Names go through a renaming (see :mod:`slugs_bridge.names`).
"""

from __future__ import annotations

from collections.abc import Mapping

from gaitc.ir.formula import (
    Add,
    And,
    Compare,
    Const,
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
)

# Binding strength in SLUGS's grammar: higher binds tighter; comparisons are atoms.
_LEVEL: dict[type, int] = {Iff: 1, Implies: 2, Xor: 3, Or: 4, And: 5, Not: 7, Next: 7}
_SYMBOL: dict[type, str] = {Iff: " <-> ", Implies: " -> ", Xor: " ^ ", Or: " | ", And: " & "}

_Piece = Node | str


def _level(node: Node) -> int:
    return _LEVEL.get(type(node), 9)


def _bracketed(node: Node, bracket: bool) -> list[_Piece]:
    return ["(", node, ")"] if bracket else [node]


def emit_infix(
    expr: Node, as_next: bool = False, names: Mapping[str, str] | None = None
) -> str:
    """A formula in structuredslugs infix syntax, with the fewest brackets that keep its shape.

    With ``as_next`` a primed variable ``x'`` is written ``X x`` (readable LTL, not SLUGS);
    ``names`` maps spec names to written names.  Raises :class:`ValueError` for a negative
    constant and for nodes that cannot stand in a section (``always``, ``eventually``).
    """
    rename = names or {}
    out: list[str] = []
    stack: list[_Piece] = [expr]
    while stack:
        item = stack.pop()
        if isinstance(item, str):
            out.append(item)
            continue
        pieces = _pieces(item, as_next, rename)
        if isinstance(pieces, str):
            out.append(pieces)
        else:
            stack.extend(reversed(pieces))
    return "".join(out)


def _pieces(node: Node, as_next: bool, names: Mapping[str, str]) -> str | list[_Piece]:
    """The text of a leaf, or what ``node`` is written as: literals and child nodes."""
    if isinstance(node, (Var, IntVar)):
        name = names.get(node.name, node.name)
        if not node.primed:
            return name
        return f"X {name}" if as_next else name + "'"
    if isinstance(node, Const):
        return "TRUE" if node.value else "FALSE"
    if isinstance(node, IntConst):
        if node.value < 0:
            raise ValueError(
                f"cannot write the negative constant {node.value} in structuredslugs"
            )
        return str(node.value)
    if isinstance(node, (Not, Next)):
        sign = "!" if isinstance(node, Not) else "X "
        return [sign, *_bracketed(node.arg, _level(node.arg) < _level(node))]
    if isinstance(node, (And, Or)):
        if len(node.args) < 2:
            return [node.args[0]] if node.args else ("TRUE" if isinstance(node, And) else "FALSE")
        level = _level(node)
        pieces: list[_Piece] = []
        for index, arg in enumerate(node.args):
            if index:
                pieces.append(_SYMBOL[type(node)])
            pieces.extend(_bracketed(arg, _level(arg) <= level))
        return pieces
    if isinstance(node, (Iff, Implies, Xor)):
        level = _level(node)
        return [*_bracketed(node.left, _level(node.left) < level), _SYMBOL[type(node)],
                *_bracketed(node.right, _level(node.right) <= level)]
    if isinstance(node, Compare):
        return [node.left, f" {node.op} ", node.right]
    if isinstance(node, Add):
        # '+' is right-recursive in SLUGS's grammar, so a sum on the left needs brackets.
        return [*_bracketed(node.left, isinstance(node.left, Add)), " + ", node.right]
    if isinstance(node, Term):
        raise ValueError(f"not an integer term: {node!r}")
    raise ValueError(
        f"cannot write {type(node).__name__} in structuredslugs: sections hold state and "
        "transition formulas only"
    )
