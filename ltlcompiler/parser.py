"""The .gait parser: ``gait.lark`` (LALR) plus a Transformer building :mod:`ltlcompiler.syntax`.

The only module that imports lark.  Lark's exceptions are mapped to
:class:`SpecSyntaxError` (or :class:`FormulaError`) with ``file:line:col`` and a
message saying what was expected; lark objects never leave this module.
"""

from __future__ import annotations

from dataclasses import replace
from functools import cache
from importlib import resources
from typing import Any

from lark import Lark, Token, Transformer, v_args
from lark.exceptions import (
    UnexpectedCharacters,
    UnexpectedEOF,
    UnexpectedInput,
    UnexpectedToken,
    VisitError,
)
from lark.lexer import PatternStr
from lark.tree import Meta

from diagnostics import FormulaError, GaitcError, Span, SpecSyntaxError
from gr1 import formula as f
from ltlcompiler import syntax as s

STATEMENT_KEYWORDS = (
    "assume", "block", "cache", "caches", "correction", "edge", "gait", "grid", "guarantee",
    "hazard", "leg", "legs", "region", "regions", "robot", "start", "visit",
)  # fmt: skip
_OPERATORS = ("&", "|", "^", "->", "<->", "and", "or", "xor", "until")
_TERMINAL_WORDS = {
    "NAME": "a name",
    "INT": "a number",
    "STRING": 'a string in double quotes',
    "AXIS": "an axis such as +x or -y",
    "$END": "end of file",
}


@cache
def _lark() -> Lark:
    text = resources.files("ltlcompiler").joinpath("gait.lark").read_text(encoding="utf-8")
    return Lark(
        text,
        parser="lalr",
        lexer="contextual",
        propagate_positions=True,
        maybe_placeholders=True,
        lexer_callbacks={"NAME": _reserved},
    )


def _reserved(tok: Token) -> Token:
    """'always'/'eventually' lexed as a name: they sit where GR(1) forbids them."""
    if tok in ("always", "eventually"):
        raise FormulaError(
            f"'{tok}' may only start an assume or guarantee: GR(1) allows 'always φ' (safety) "
            "and 'always eventually φ' (liveness), never a temporal word inside a formula or "
            "as a name",
            _token_span("", tok),
        )
    return tok


# ---------------------------------------------------------------- spans
def _meta_span(file: str, meta: Meta) -> Span | None:
    if getattr(meta, "empty", True):
        return None
    return Span(file, meta.line, meta.column, meta.end_line, meta.end_column - 1)


def _token_span(file: str, tok: Token) -> Span:
    line = tok.line or 1
    column = tok.column or 1
    end_column = (tok.end_column or column + 1) - 1
    return Span(file, line, column, tok.end_line or line, end_column)


# ---------------------------------------------------------------- tree -> syntax
@v_args(meta=True)
class _Builder(Transformer[Token, s.SpecFile]):
    """Turns lark's parse tree into syntax nodes; method names are the grammar's rules."""

    def __init__(self, file: str) -> None:
        super().__init__()
        self.file = file

    def _sp(self, meta: Meta) -> Span | None:
        return _meta_span(self.file, meta)

    def _name(self, tok: Token) -> s.Name:
        return s.Name(str(tok), span=_token_span(self.file, tok))

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
        return s.Cell(int(ch[0]), int(ch[1]), span=self._sp(meta))

    # statements
    def start(self, meta: Meta, ch: list[s.Statement]) -> s.SpecFile:
        return s.SpecFile(tuple(ch), file=self.file)

    def robot_decl(self, meta: Meta, ch: list[Token]) -> s.RobotDecl:
        return s.RobotDecl(str(ch[0])[1:-1], span=self._sp(meta))

    def legs_decl(self, meta: Meta, ch: list[Any]) -> s.LegsDecl:
        health: Token = ch[1]
        return s.LegsDecl(
            ch[0], int(health), health_span=_token_span(self.file, health), span=self._sp(meta)
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
        return s.GridDecl(int(ch[0]), int(ch[1]), ch[2], span=self._sp(meta))

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

    def hazard_decl(self, meta: Meta, ch: list[Any]) -> s.HazardDecl:
        regions = ch[1] if ch[1] is not None else ()
        return s.HazardDecl(self._name(ch[0]), regions, span=self._sp(meta))

    def health_init(self, meta: Meta, ch: list[Any]) -> s.HealthInit:
        value: Token = ch[1]
        return s.HealthInit(
            self._item(ch[0]),
            int(value),
            value_span=_token_span(self.file, value),
            span=self._sp(meta),
        )

    def start_decl(self, meta: Meta, ch: list[Any]) -> s.StartDecl:
        inits = tuple(c for c in ch[1:] if c is not None)
        return s.StartDecl(self._item(ch[0]), inits, span=self._sp(meta))

    def visit_decl(self, meta: Meta, ch: list[Any]) -> s.VisitDecl:
        return s.VisitDecl(ch[0], span=self._sp(meta))

    def assume_decl(self, meta: Meta, ch: list[f.Expr]) -> s.AssumeDecl:
        return s.AssumeDecl(ch[0], span=self._sp(meta))

    def guarantee_decl(self, meta: Meta, ch: list[f.Expr]) -> s.GuaranteeDecl:
        return s.GuaranteeDecl(ch[0], span=self._sp(meta))

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
        return f.Or((*left, ch[1]), span=self._sp(meta))

    def xor(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Xor(ch[0], ch[1], span=self._sp(meta))

    def and_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        left = ch[0].args if isinstance(ch[0], f.And) else (ch[0],)
        return f.And((*left, ch[1]), span=self._sp(meta))

    def not_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Not(ch[0], span=self._sp(meta))

    def next_(self, meta: Meta, ch: list[f.Expr]) -> f.Expr:
        return f.Next(ch[0], span=self._sp(meta))

    def var(self, meta: Meta, ch: list[Token]) -> f.Expr:
        return f.Var(str(ch[0]), span=_token_span(self.file, ch[0]))

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
            f.IntVar(str(leg), span=_token_span(self.file, leg)),
            f.IntConst(int(value), span=_token_span(self.file, value)),
            span=self._sp(meta),
        )

    def failed(self, meta: Meta, ch: list[Token]) -> f.Expr:
        leg = ch[0]
        return f.Compare(
            "=",
            f.IntVar(str(leg), span=_token_span(self.file, leg)),
            f.IntConst(1, span=self._sp(meta)),
            span=self._sp(meta),
        )


# ---------------------------------------------------------------- errors
def _check_brackets(text: str, file: str) -> None:
    """Report an unclosed '(' or an unmatched ')' where it is, before lark gets lost."""
    stack: list[Span] = []
    in_comment = in_string = False
    line, col = 1, 0
    for ch in text:
        col += 1
        if ch == "\n":
            line, col = line + 1, 0
            in_comment = in_string = False
            continue
        if in_comment:
            continue
        if in_string:
            in_string = ch != '"'
            continue
        if ch == "#":
            in_comment = True
        elif ch == '"':
            in_string = True
        elif ch == "(":
            stack.append(Span(file, line, col, line, col))
        elif ch == ")":
            if not stack:
                here = Span(file, line, col, line, col)
                raise SpecSyntaxError("')' has no matching '('; remove it or add '('", here)
            stack.pop()
    if stack:
        raise SpecSyntaxError("'(' is never closed; add a matching ')'", stack[-1])


def _describe_terminal(name: str) -> str:
    if name in _TERMINAL_WORDS:
        return _TERMINAL_WORDS[name]
    try:
        pattern = _lark().get_terminal(name).pattern
    except KeyError:
        return name.lower()
    if isinstance(pattern, PatternStr):
        return f"'{pattern.value}'"
    return name.lower()


def _describe_expected(expected: set[str]) -> str:
    words = sorted({_describe_terminal(name) for name in expected})
    statements = [w for w in words if w.strip("'") in STATEMENT_KEYWORDS]
    if len(statements) >= 5:
        words = [w for w in words if w not in statements] + ["a new statement"]
    operators = [w for w in words if w.strip("'") in _OPERATORS]
    if len(operators) >= 3:
        words = ["an operator such as & or ->"] + [w for w in words if w not in operators]
    if len(words) == 1:
        return words[0]
    return ", ".join(words[:-1]) + " or " + words[-1]


def _describe_token(tok: Token) -> str:
    if tok.type == "$END":
        return "end of file"
    if tok.type == "NAME":
        return f"name '{tok}'"
    if tok.type == "INT":
        return f"number '{tok}'"
    if tok.type == "STRING":
        return f"string {tok}"
    return f"'{tok}'"


def _end_span(text: str, file: str) -> Span:
    lines = text.splitlines() or [""]
    return Span(file, len(lines), len(lines[-1]) + 1)


def _syntax_error(err: UnexpectedInput, text: str, file: str) -> GaitcError:
    if isinstance(err, UnexpectedCharacters):
        here = Span(file, err.line, err.column, err.line, err.column)
        pos = err.pos_in_stream if err.pos_in_stream is not None else -1
        char = text[pos] if 0 <= pos < len(text) else "?"
        if char == '"':
            return SpecSyntaxError("unterminated string: add the closing '\"' on this line", here)
        shown = repr(char)[1:-1] if not char.isprintable() else char
        return SpecSyntaxError(
            f"unexpected character '{shown}': names use letters, digits and '_', "
            "comments start with '#'",
            here,
        )
    if isinstance(err, UnexpectedToken):
        tok = err.token
        expected = set(err.accepts or err.expected or ())
        if tok.type == "$END":
            return SpecSyntaxError(
                f"unexpected end of file; expected {_describe_expected(expected)}",
                _end_span(text, file),
            )
        return SpecSyntaxError(
            f"unexpected {_describe_token(tok)}; expected {_describe_expected(expected)}",
            _token_span(file, tok),
        )
    if isinstance(err, UnexpectedEOF):
        expected = set(err.expected or ())
        return SpecSyntaxError(
            f"unexpected end of file; expected {_describe_expected(expected)}",
            _end_span(text, file),
        )
    return SpecSyntaxError(str(err).splitlines()[0], _end_span(text, file))


# ---------------------------------------------------------------- public API
def parse(text: str, file: str = "<string>") -> s.SpecFile:
    """Parse .gait source ``text`` (reported as ``file``) into a :class:`~syntax.SpecFile`.

    Raises :class:`SpecSyntaxError` or :class:`FormulaError` with a span on bad input.
    """
    _check_brackets(text, file)
    try:
        tree = _lark().parse(text)
    except UnexpectedInput as err:
        raise _syntax_error(err, text, file) from None
    except FormulaError as err:  # from the lexer callback, which does not know the file
        span = None if err.span is None else replace(err.span, file=file)
        raise FormulaError(err.message, span) from None
    try:
        return _Builder(file).transform(tree)
    except VisitError as err:
        if isinstance(err.orig_exc, GaitcError):
            raise err.orig_exc from None
        raise
