"""The .gait parser: ``gait.lark`` (LALR) plus :mod:`ltlcompiler.parse_tree`, which builds
:mod:`ltlcompiler.syntax` from lark's tree without recursion.

With :mod:`ltlcompiler.parse_tree`, the only module that imports lark.  Lark's exceptions
are mapped to :class:`SpecSyntaxError` (or :class:`FormulaError`) with ``file:line:col``
and a message saying what was expected; lark objects never leave the two modules.  LALR
parsing keeps its own stack, so formulas of any depth parse; the builder refuses those
deeper than :data:`~ltlcompiler.parse_tree.MAX_NESTING`.
"""

from __future__ import annotations

from dataclasses import replace
from functools import cache
from importlib import resources

from lark import Lark, Token
from lark.exceptions import (
    UnexpectedCharacters,
    UnexpectedEOF,
    UnexpectedInput,
    UnexpectedToken,
)
from lark.lexer import PatternStr

from diagnostics import FormulaError, GaitcError, Span, SpecSyntaxError, source_lines
from ltlcompiler import syntax as s
from ltlcompiler.parse_tree import build, token_span

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
            token_span("", tok),
        )
    return tok


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
    lines = source_lines(text) or [""]
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
            token_span(file, tok),
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
    return build(tree, file)
