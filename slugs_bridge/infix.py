"""Infix formula parser for ``.structuredslugs`` lines (SLUGS's StructuredSlugsParser grammar).

Precedence, lowest first, all binary operators left-associative as in SLUGS's
tools/StructuredSlugsParser/grammar.wi: ``<->``, ``->``, ``^``, ``|``, ``&``, unary
(``! ~ X next``); comparisons ``= != < <= > >=`` of ``+`` sums are atoms.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass

from diagnostics import FormulaError, SlugsFormatError, Span
from gr1.formula import (
    Add,
    And,
    Compare,
    Const,
    Expr,
    Iff,
    Implies,
    IntConst,
    IntVar,
    Next,
    Not,
    Or,
    Term,
    Var,
    Xor,
    push_next,
)

KEYWORDS = frozenset({"X", "F", "G", "U", "W", "TRUE", "FALSE", "next"})
IDENT = re.compile(r"[A-Za-z_.@][A-Za-z0-9_.@]*'?")
_LEXEME = re.compile(
    r"\s*(?:(?P<ident>[A-Za-z_.@][A-Za-z0-9_.@]*'?)|(?P<num>[0-9]+)"
    r"|(?P<op><-->|<->|-->|->|&&|\|\||/\\|\\/|==|!=|<=|>=|\[\]|<>|[!~&|^()\[\]=<>+\-*]))"
)
_CLOSING = {"(": ")", "[": "]"}
_ALIASES = {"&&": "&", "/\\": "&", "||": "|", "\\/": "|", "~": "!", "-->": "->", "<-->": "<->"}
_TEMPORAL = {
    "F": "'F' (eventually)", "<>": "'<>' (eventually)", "G": "'G' (always)",
    "[]": "'[]' (always)", "U": "'U' (until)", "W": "'W' (weak until)",
}


@dataclass(frozen=True)
class Token:
    kind: str  # "ident", "num", "op" or "end"
    text: str  # operator aliases are normalised (``&&`` -> ``&``)
    span: Span


def tokenize(text: str, filename: str, line: int) -> list[Token]:
    """Split one formula line into tokens; an unknown character is a :class:`SlugsFormatError`."""
    out: list[Token] = []
    pos = 0
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos >= len(text):
            break
        m = _LEXEME.match(text, pos)
        if m is None or m.lastgroup is None:
            raise SlugsFormatError(
                f"unexpected character '{text[pos]}' in a formula",
                Span(filename, line, pos + 1, line, pos + 1),
            )
        kind = m.lastgroup
        raw = m.group(kind)
        start = m.start(kind)
        span = Span(filename, line, start + 1, line, start + len(raw))
        if raw == "==":
            raise SlugsFormatError("'==' is not an operator here; write '=' for equality", span)
        out.append(Token(kind, _ALIASES.get(raw, raw), span))
        pos = m.end()
    end = len(text.rstrip()) + 1
    out.append(Token("end", "", Span(filename, line, end, line, end)))
    return out


class InfixParser:
    """Recursive-descent parser for one line; ``booleans``/``integers`` are the declared names."""

    def __init__(
        self, tokens: list[Token], booleans: set[str], integers: Mapping[str, object]
    ) -> None:
        self.tokens = tokens
        self.pos = 0
        self.booleans = booleans
        self.integers = integers

    # ------------------------------------------------------------ helpers
    @property
    def tok(self) -> Token:
        return self.tokens[self.pos]

    def advance(self) -> Token:
        tok = self.tokens[self.pos]
        self.pos += 1
        return tok

    def fail(self, expected: str) -> SlugsFormatError:
        tok = self.tok
        if tok.kind == "end":
            return SlugsFormatError(f"the formula ends too early: expected {expected}", tok.span)
        return SlugsFormatError(f"unexpected '{tok.text}': expected {expected}", tok.span)

    def expect_close(self, opener: Token) -> None:
        closing = _CLOSING[opener.text]
        if self.tok.text != closing:
            if self.tok.kind == "end":
                raise SlugsFormatError(
                    f"missing '{closing}' to close the '{opener.text}' at column "
                    f"{opener.span.column}",
                    opener.span,
                )
            raise self.fail(f"'{closing}' to close the '{opener.text}' at column "
                            f"{opener.span.column}")
        self.advance()

    # ------------------------------------------------------------ Boolean levels
    def parse_line(self) -> Expr:
        expr = self.biimplication()
        if self.tok.kind != "end":
            if self.tok.text in (")", "]"):
                raise SlugsFormatError(
                    f"unexpected '{self.tok.text}' with no matching opening bracket",
                    self.tok.span,
                )
            raise self.fail("an operator or the end of the line")
        try:
            return push_next(expr)
        except FormulaError as err:
            raise SlugsFormatError(err.message, err.span) from None

    def _left_assoc(self, op: str, sub: str) -> Expr:
        left: Expr = getattr(self, sub)()
        while self.tok.text == op:
            span = self.advance().span
            right: Expr = getattr(self, sub)()
            if op == "<->":
                left = Iff(left, right, span=span)
            elif op == "->":
                left = Implies(left, right, span=span)
            else:
                left = Xor(left, right, span=span)
        return left

    def biimplication(self) -> Expr:
        return self._left_assoc("<->", "implication")

    def implication(self) -> Expr:
        return self._left_assoc("->", "xor")

    def xor(self) -> Expr:
        return self._left_assoc("^", "disjunction")

    def _chain(self, op: str, sub: str) -> Expr:
        first: Expr = getattr(self, sub)()
        if self.tok.text != op:
            return first
        span = self.tok.span
        args = [first]
        while self.tok.text == op:
            self.advance()
            args.append(getattr(self, sub)())
        return (And if op == "&" else Or)(tuple(args), span=span)

    def disjunction(self) -> Expr:
        return self._chain("|", "conjunction")

    def conjunction(self) -> Expr:
        return self._chain("&", "binary_temporal")

    def binary_temporal(self) -> Expr:
        expr = self.unary()
        if self.tok.text in ("U", "W"):
            raise self.temporal(self.tok)
        return expr

    def temporal(self, tok: Token) -> SlugsFormatError:
        return SlugsFormatError(
            f"temporal operator {_TEMPORAL[tok.text]} is outside GR(1): a section line is "
            "a state or transition formula (use next/X or primes only)",
            tok.span,
        )

    def unary(self) -> Expr:
        tok = self.tok
        if tok.text == "!":
            self.advance()
            return Not(self.unary(), span=tok.span)
        if tok.text in ("X", "next"):
            self.advance()
            return Next(self.unary(), span=tok.span)
        if tok.text in _TEMPORAL and tok.kind != "num":
            raise self.temporal(tok)
        return self.atomic()

    def atomic(self) -> Expr:
        tok = self.tok
        if tok.text in ("TRUE", "FALSE"):
            self.advance()
            return Const(tok.text == "TRUE", span=tok.span)
        if tok.text in ("(", "["):
            if tok.text == "(" and self.starts_number():
                saved = self.pos
                try:
                    return self.comparison()
                except SlugsFormatError:
                    self.pos = saved
            self.advance()
            inner = self.biimplication()
            self.expect_close(tok)
            return inner
        if tok.kind == "num":
            if self.tokens[self.pos + 1].text in ("=", "!=", "<", "<=", ">", ">="):
                return self.comparison()
            if tok.text in ("0", "1"):
                self.advance()
                return Const(tok.text == "1", span=tok.span)
            raise SlugsFormatError(
                f"the number {tok.text} is not a formula; compare it with an integer "
                f"variable, e.g. 'x = {tok.text}'",
                tok.span,
            )
        if tok.kind == "ident" and tok.text not in KEYWORDS:
            name = tok.text.rstrip("'")
            if name in self.integers:
                return self.comparison()
            if name in self.booleans:
                self.advance()
                return Var(name, tok.text.endswith("'"), span=tok.span)
            raise self.unknown(tok)
        raise self.fail("a variable, TRUE, FALSE, a comparison or '('")

    def unknown(self, tok: Token) -> SlugsFormatError:
        name = tok.text.rstrip("'")
        if "@" in name and name.split("@")[0] in self.integers:
            return SlugsFormatError(
                f"'{name}' is a bit of integer variable '{name.split('@')[0]}'; refer to the "
                "integer by name instead",
                tok.span,
            )
        return SlugsFormatError(
            f"unknown variable '{name}'; declare it under [INPUT] or [OUTPUT]", tok.span
        )

    def starts_number(self) -> bool:
        i = self.pos
        while self.tokens[i].text == "(":
            i += 1
        tok = self.tokens[i]
        return tok.kind == "num" or (
            tok.kind == "ident" and tok.text.rstrip("'") in self.integers
        )

    # ------------------------------------------------------------ integer terms
    def comparison(self) -> Expr:
        left = self.sum()
        op = self.tok
        if op.text not in ("=", "!=", "<", "<=", ">", ">="):
            raise self.fail("a comparison (=, !=, <, <=, >, >=) after an integer expression")
        self.advance()
        right = self.sum()
        return Compare(op.text, left, right, span=op.span)

    def sum(self) -> Term:
        left = self.product()
        tok = self.tok
        if tok.text == "+":
            self.advance()
            return Add(left, self.sum(), span=tok.span)
        if tok.text == "-":
            raise SlugsFormatError(
                "subtraction is not supported (SLUGS does not support it either); move the "
                "term to the other side, e.g. 'x + 1 = y' instead of 'x = y - 1'",
                tok.span,
            )
        return left

    def product(self) -> Term:
        term = self.atomic_term()
        if self.tok.text == "*":
            raise SlugsFormatError(
                "multiplication is not supported; write repeated additions instead",
                self.tok.span,
            )
        return term

    def atomic_term(self) -> Term:
        tok = self.tok
        if tok.kind == "num":
            self.advance()
            return IntConst(int(tok.text), span=tok.span)
        if tok.text == "(":
            self.advance()
            inner = self.sum()
            self.expect_close(tok)
            return inner
        if tok.kind == "ident" and tok.text not in KEYWORDS:
            name = tok.text.rstrip("'")
            if name in self.integers:
                self.advance()
                return IntVar(name, tok.text.endswith("'"), span=tok.span)
            if name in self.booleans:
                raise SlugsFormatError(
                    f"Boolean variable '{name}' cannot be used in arithmetic; only integer "
                    "variables (name:MIN...MAX) can",
                    tok.span,
                )
            raise self.unknown(tok)
        raise self.fail("an integer variable, a number or '('")


def parse_infix(
    text: str, filename: str, line: int, booleans: set[str], integers: Mapping[str, object]
) -> Expr:
    """Parse one infix formula line; ``next``/``X`` are pushed into primes."""
    tokens = tokenize(text, filename, line)
    parser = InfixParser(tokens, booleans, integers)
    try:
        return parser.parse_line()
    except RecursionError:
        raise SlugsFormatError(
            "this formula nests too deeply for the reader (brackets or prefix operators "
            "hundreds of levels deep); split it into several lines",
            Span(filename, line, tokens[0].span.column, line, tokens[-1].span.column),
        ) from None
