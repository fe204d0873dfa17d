"""Writer of infix formulas: structuredslugs lines and the bodies of the readable LTL text.

The fewest brackets that keep a formula's shape under SLUGS's grammar (see
:mod:`slugs_bridge.infix`), written from an explicit stack, so formulas nested any number
of levels deep are fine.  Names go through a renaming (see :mod:`slugs_bridge.names`).
"""

from __future__ import annotations

from collections.abc import Mapping

from gaitc.ir.formula import (
    Add,
    Always,
    And,
    Compare,
    Const,
    Eventually,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Node,
    Not,
    Or,
    Var,
    Xor,
    node_kind,
    unreachable,
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
    kind = node_kind(node)
    match kind:
        case Var() | IntVar():
            name = names.get(kind.name, kind.name)
            if not kind.primed:
                return name
            return f"X {name}" if as_next else name + "'"
        case Const():
            return "TRUE" if kind.value else "FALSE"
        case IntConst():
            if kind.value < 0:
                raise ValueError(
                    f"cannot write the negative constant {kind.value} in structuredslugs")
            return str(kind.value)
        case Not() | Next():
            sign = "!" if isinstance(kind, Not) else "X "
            return [sign, *_bracketed(kind.arg, _level(kind.arg) < _level(kind))]
        case And() | Or():
            if len(kind.args) < 2:
                return [kind.args[0]] if kind.args else (
                    "TRUE" if isinstance(kind, And) else "FALSE")
            level = _level(kind)
            pieces: list[_Piece] = []
            for index, arg in enumerate(kind.args):
                if index:
                    pieces.append(_SYMBOL[type(kind)])
                pieces.extend(_bracketed(arg, _level(arg) <= level))
            return pieces
        case Iff() | Implies() | Xor():
            level = _level(kind)
            return [*_bracketed(kind.left, _level(kind.left) < level), _SYMBOL[type(kind)],
                    *_bracketed(kind.right, _level(kind.right) <= level)]
        case Compare():
            return [kind.left, f" {kind.op} ", kind.right]
        case Add():
            # '+' is right-recursive in SLUGS's grammar, so a sum on the left needs brackets.
            return [*_bracketed(kind.left, isinstance(kind.left, Add)), " + ", kind.right]
        case Always() | Eventually():
            raise ValueError(
                f"cannot write {type(kind).__name__} in structuredslugs: sections hold state "
                "and transition formulas only")
        case _:
            unreachable(kind)
