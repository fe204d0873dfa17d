"""lark's parse tree of a .gait file to :mod:`ltlcompiler.syntax` nodes, without recursion.

:func:`build` walks the tree children first with an explicit stack and calls the
:class:`_Builder` method named after each rule, so a formula nested thousands of levels
deep builds like a shallow one.  Formulas deeper than :data:`MAX_NESTING` levels are
refused with a positioned :class:`FormulaError`.  With :mod:`ltlcompiler.parser`, the
only module that touches lark objects; none of them leaves the two.
"""

from __future__ import annotations

from typing import Any

from lark import Token, Tree
from lark.tree import Meta

from gaitc.diagnostics import FormulaError, Span, SpecSyntaxError
from gaitc.ir import formula as f
from gaitc.ir.traversal import Memo, fold
from ltlcompiler import syntax as s

#: The deepest formula a .gait file may hold, counted in operators from the top of an
#: assume or guarantee down to an atom (a chain of ``&`` or ``|`` counts once,
#: parentheses do not count).  Measured in docs/language.md.
MAX_NESTING = 100_000


# ---------------------------------------------------------------- spans
def meta_span(file: str, meta: Meta) -> Span | None:
    if getattr(meta, "empty", True):
        return None
    return Span(file, meta.line, meta.column, meta.end_line, meta.end_column - 1)


MAX_DIGITS = 9  # numbers in a .gait file (health levels, grid sizes, cells): below 10**9


def number(file: str, tok: Token) -> int:
    """The value of a NUMBER token, refused with its position when it has too many digits."""
    text = str(tok)
    if len(text) > MAX_DIGITS:
        raise SpecSyntaxError(f"the number has {len(text)} digits; numbers in a .gait file "
                              f"have at most {MAX_DIGITS}", token_span(file, tok))
    return int(text)


def token_span(file: str, tok: Token) -> Span:
    line = tok.line or 1
    column = tok.column or 1
    end_column = (tok.end_column or column + 1) - 1
    return Span(file, line, column, tok.end_line or line, end_column)


# ---------------------------------------------------------------- tree -> syntax
class _Builder:
    """Turns lark's parse tree into syntax nodes; method names are the grammar's rules,
    each called with the rule's position and its children already built."""

    def __init__(self, file: str) -> None:
        self.file = file

    def _sp(self, meta: Meta) -> Span | None:
        return meta_span(self.file, meta)

    def _name(self, tok: Token) -> s.Name:
        return s.Name(str(tok), span=token_span(self.file, tok))

    def _item(self, item: Any) -> Any:
        """A NAME token becomes a Name; syntax nodes pass through."""
        return self._name(item) if isinstance(item, Token) else item

    # names and cells
    def name_list(self, meta: Meta, ch: list[Any]) -> tuple[s.NameItem, ...]:
        return tuple(self._item(c) for c in ch)

    def name_range(self, meta: Meta, ch: list[Token]) -> s.NameRange:
        return s.NameRange(self._name(ch[0]), self._name(ch[1]), span=self._sp(meta))

    def ref_list(self, meta: Meta, ch: list[Any]) -> tuple[s.RegionRef, ...]:
        return tuple(self._item(c) for c in ch)

    def cell(self, meta: Meta, ch: list[Token]) -> s.Cell:
        return s.Cell(number(self.file, ch[0]), number(self.file, ch[1]), span=self._sp(meta))

    # statements
    def start(self, meta: Meta, ch: list[s.Statement]) -> s.SpecFile:
        return s.SpecFile(tuple(ch), file=self.file)

    def robot_decl(self, meta: Meta, ch: list[Token]) -> s.RobotDecl:
        return s.RobotDecl(str(ch[0])[1:-1], span=self._sp(meta))

    def legs_decl(self, meta: Meta, ch: list[Any]) -> s.LegsDecl:
        health: Token = ch[1]
        return s.LegsDecl(
            ch[0], number(self.file, health), health_span=token_span(self.file, health),
            span=self._sp(meta),
        )

    def uses(self, meta: Meta, ch: list[Any]) -> tuple[s.NameItem, ...]:
        return tuple(ch[0])

    def direction(self, meta: Meta, ch: list[Token]) -> s.Direction:
        return s.Direction(str(ch[0]), span=self._sp(meta))

    def moves_direction(self, meta: Meta, ch: list[s.Direction]) -> tuple[str, tuple[Any, ...]]:
        return ("directions", tuple(ch))

    def moves_transitions(self, meta: Meta, ch: list[s.Arrow]) -> tuple[str, tuple[Any, ...]]:
        return ("transitions", tuple(ch))

    def arrow(self, meta: Meta, ch: list[Any]) -> s.Arrow:
        return s.Arrow(self._item(ch[0]), self._item(ch[1]), span=self._sp(meta))

    def primitive_valves(self, meta: Meta, ch: list[Token]) -> s.ValvesPrimitive:
        return s.ValvesPrimitive(tuple(self._name(t) for t in ch), span=self._sp(meta))

    def primitive_robot(self, meta: Meta, ch: list[Token | None]) -> s.RobotPrimitive:
        robot, axis, method = ch
        return s.RobotPrimitive(
            str(robot)[1:-1],
            None if axis is None else str(axis),
            None if method is None else self._name(method),
            span=self._sp(meta),
        )

    def gait_decl(self, meta: Meta, ch: list[Any]) -> s.GaitDecl:
        correction, name, legs, moves, primitive = ch
        kind, items = moves if moves is not None else ("", ())
        return s.GaitDecl(
            self._name(name),
            correction is not None,
            legs,
            directions=items if kind == "directions" else (),
            transitions=items if kind == "transitions" else (),
            primitive=primitive,
            span=self._sp(meta),
        )

    def grid_decl(self, meta: Meta, ch: list[Any]) -> s.GridDecl:
        return s.GridDecl(number(self.file, ch[0]), number(self.file, ch[1]), ch[2],
                          span=self._sp(meta))

    def block_decl(self, meta: Meta, ch: list[Any]) -> s.BlockDecl:
        return s.BlockDecl(ch[0], span=self._sp(meta))

    def region_decl(self, meta: Meta, ch: list[Any]) -> s.RegionDecl:
        return s.RegionDecl(ch[0], span=self._sp(meta))

    def edge_arrow(self, meta: Meta, ch: list[Token]) -> bool:
        return str(ch[0]) == "<->"

    def edge_by(self, meta: Meta, ch: list[Token]) -> tuple[s.Name, ...]:
        return tuple(self._name(t) for t in ch)

    def edge_direction(self, meta: Meta, ch: list[s.Direction]) -> s.Direction:
        return ch[0]

    def edge_decl(self, meta: Meta, ch: list[Any]) -> s.EdgeDecl:
        source, both, target, label = ch
        return s.EdgeDecl(
            self._item(source),
            self._item(target),
            both,
            gaits=label if isinstance(label, tuple) else (),
            direction=label if isinstance(label, s.Direction) else None,
            span=self._sp(meta),
        )

    def cache_decl(self, meta: Meta, ch: list[Any]) -> s.CacheDecl:
        return s.CacheDecl(ch[0], span=self._sp(meta))

    def wears(self, meta: Meta, ch: list[Token]) -> Token:
        return ch[0]

    def hazard_decl(self, meta: Meta, ch: list[Any]) -> s.HazardDecl:
        name, refs, amount = ch
        regions = refs if refs is not None else ()
        if amount is None:
            return s.HazardDecl(self._name(name), regions, span=self._sp(meta))
        return s.HazardDecl(self._name(name), regions, number(self.file, amount),
                            wears_span=token_span(self.file, amount), span=self._sp(meta))

    def health_init(self, meta: Meta, ch: list[Any]) -> s.HealthInit:
        value: Token = ch[1]
        return s.HealthInit(
            self._item(ch[0]),
            number(self.file, value),
            value_span=token_span(self.file, value),
            span=self._sp(meta),
        )

    def start_decl(self, meta: Meta, ch: list[Any]) -> s.StartDecl:
        inits = tuple(c for c in ch[1:] if c is not None)
        return s.StartDecl(self._item(ch[0]), inits, span=self._sp(meta))

    def visit_decl(self, meta: Meta, ch: list[Any]) -> s.VisitDecl:
        return s.VisitDecl(ch[0], span=self._sp(meta))

    def assume_decl(self, meta: Meta, ch: list[f.Expr]) -> s.AssumeDecl:
        return s.AssumeDecl(_shallow(ch[0]), span=self._sp(meta))

    def guarantee_decl(self, meta: Meta, ch: list[f.Expr]) -> s.GuaranteeDecl:
        return s.GuaranteeDecl(_shallow(ch[0]), span=self._sp(meta))

    # formulas
    def always(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Always(ch[0], span=self._sp(meta))

    def eventually(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Eventually(ch[0], span=self._sp(meta))

    def until(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        raise FormulaError(
            "'until' is outside GR(1): write 'always φ' (safety) or 'always eventually φ' "
            "(liveness) instead",
            self._sp(meta),
        )

    def iff(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Iff(ch[0], ch[1], span=self._sp(meta))

    def implies(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Implies(ch[0], ch[1], span=self._sp(meta))

    def or_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        left = ch[0].args if isinstance(ch[0], f.Or) else (ch[0],)
        return f.Or((*left, *ch[1:]), span=self._sp(meta))

    def xor(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Xor(ch[0], ch[1], span=self._sp(meta))

    def and_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        left = ch[0].args if isinstance(ch[0], f.And) else (ch[0],)
        return f.And((*left, *ch[1:]), span=self._sp(meta))

    def not_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Not(ch[0], span=self._sp(meta))

    def next_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Next(ch[0], span=self._sp(meta))

    def var(self, meta: Meta, ch: list[Token]) -> f.Expr:
        return f.Var(str(ch[0]), span=token_span(self.file, ch[0]))

    def true(self, meta: Meta, ch: list[Token]) -> f.Expr:
        return f.Const(True, span=self._sp(meta))

    def false(self, meta: Meta, ch: list[Token]) -> f.Expr:
        return f.Const(False, span=self._sp(meta))

    def compare_op(self, meta: Meta, ch: list[Token]) -> str:
        return str(ch[0])

    def compare(self, meta: Meta, ch: list[Any]) -> f.Expr:
        leg, op, value = ch
        return f.Compare(
            op,
            f.IntVar(str(leg), span=token_span(self.file, leg)),
            f.IntConst(number(self.file, value), span=token_span(self.file, value)),
            span=self._sp(meta),
        )

    def failed(self, meta: Meta, ch: list[Token]) -> f.Expr:
        leg = ch[0]
        return f.Compare(
            "=",
            f.IntVar(str(leg), span=token_span(self.file, leg)),
            f.IntConst(1, span=self._sp(meta)),
            span=self._sp(meta),
        )


def _shallow(formula: f.Expr) -> f.Expr:
    """``formula``, unless it is nested deeper than :data:`MAX_NESTING` levels: then a
    FormulaError at the first subformula below the limit on its (leftmost) deepest path."""
    heights: Memo[int] = {}
    depth = fold(formula, lambda _, kids: 1 + max(kids, default=0), memo=heights)
    if depth <= MAX_NESTING:
        return formula
    node: f.Node = formula
    for _ in range(MAX_NESTING):
        node = max(node.children(), key=lambda child: heights[id(child)][1])
    raise FormulaError(
        f"formula nested {depth} levels deep; the limit is {MAX_NESTING}",
        node.span or formula.span,
        hint="split it into several assume or guarantee statements",
    )


_CHAINS = ("and_", "or_")  # left-associative rules whose chains become one n-ary node


def _collapsed(node: Tree[Token]) -> Tree[Token]:
    """A chain ``a & b & c``, which lark gives as ``and_(and_(a, b), c)``, as the one node
    ``and_(a, b, c)`` (what the rule methods would build step by step, in linear time)."""
    rights: list[Tree[Token] | Token] = []
    inner = node
    while True:
        left, right = inner.children
        rights.append(right)
        if not (isinstance(left, Tree) and left.data == node.data):
            break
        inner = left
    if len(rights) == 1:
        return node
    return Tree(node.data, [left, *reversed(rights)], node.meta)


def build(tree: Tree[Token], file: str) -> s.SpecFile:
    """The syntax tree of lark's parse ``tree`` of ``file``, built children first.

    Tokens and ``None`` placeholders reach the rule methods as they are, like in a lark
    Transformer with ``v_args(meta=True)``; a rule without a method stays a lark Tree.
    """
    builder = _Builder(file)
    values: list[Any] = []  # built subtrees, in the order they were finished
    stack: list[tuple[Tree[Token], bool]] = [(tree, False)]
    while stack:
        node, ready = stack.pop()
        if not ready and node.data in _CHAINS:
            node = _collapsed(node)
        subtrees = [c for c in node.children if isinstance(c, Tree)]
        if not ready and subtrees:
            stack.append((node, True))
            stack.extend((c, False) for c in reversed(subtrees))
            continue
        done = iter(values[len(values) - len(subtrees):])
        del values[len(values) - len(subtrees):]
        children = [next(done) if isinstance(c, Tree) else c for c in node.children]
        method = getattr(builder, str(node.data), None)
        values.append(Tree(node.data, children, node.meta) if method is None
                      else method(node.meta, children))
    result = values.pop()
    assert isinstance(result, s.SpecFile)
    return result
