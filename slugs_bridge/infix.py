"""Infix formula parser for ``.structuredslugs`` lines (SLUGS's StructuredSlugsParser grammar).

Precedence, lowest first, all binary operators left-associative as in SLUGS's
tools/StructuredSlugsParser/grammar.wi: ``<->``, ``->``, ``^``, ``|``, ``&``, unary
(``! ~ X next``); comparisons ``= != < <= > >=`` of ``+`` sums are atoms.  An
operator-precedence parser over explicit stacks, so brackets and prefix operators may nest
any number of levels deep; ``next`` is pushed into primes as the line is read.  The readable
LTL text (:mod:`slugs_bridge.ltltext`) uses it with ``X x`` read as the atom ``x'``.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import cast

from gaitc.diagnostics import SlugsFormatError, Span
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
from slugs_bridge.names import KEYWORDS as KEYWORDS
from slugs_bridge.shapes import checked_int, primed

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


_COMPARE = frozenset({"=", "!=", "<", "<=", ">", ">="})
_BINARY = {"<->": 1, "->": 2, "^": 3, "|": 4, "&": 5}
_UNARY, _COMPARISON, _PLUS = 7, 8, 9
_IN_TERMS = "an integer variable, a number or '('"
_IN_FORMULAS = "a variable, TRUE, FALSE, a comparison or '('"


_Mark = tuple[Span, str] | None


@dataclass
class _Value:
    """A parsed operand: a formula, or an integer term waiting for its comparison."""

    node: Node
    is_term: bool
    numeral: Token | None = None  # a bare number, perhaps in brackets (0 and 1 are constants)
    nested: _Mark = None  # the first 'next' applied inside
    primed: _Mark = None  # the first primed atom inside, with its name


@dataclass
class _Op:
    """An operator, or an opening bracket, waiting for its operands."""

    text: str  # "X" stands for next; "(" and "[" are brackets
    span: Span
    prec: int  # 0 for brackets
    count: int = 2  # operands of an '&' or '|' chain
    term: bool = False  # a bracket opened where only an integer term can stand


def _first(marks: list[_Mark]) -> _Mark:
    found = [m for m in marks if m is not None]
    return min(found, key=lambda m: (m[0].line, m[0].column)) if found else None


class InfixParser:
    """Parser for one line; ``booleans``/``integers`` are the declared names as written.

    ``names`` maps written names back to spec names (see :mod:`slugs_bridge.names`);
    with ``next_atoms``, ``X x`` is the atom ``x'`` wherever an atom may stand, sums too.
    """

    def __init__(
        self, tokens: list[Token], booleans: set[str], integers: Mapping[str, object],
        names: Mapping[str, str] | None = None, next_atoms: bool = False,
    ) -> None:
        self.tokens = tokens
        self.booleans = booleans
        self.integers = integers
        self.names = names or {}
        self.next_atoms = next_atoms
        self.values: list[_Value] = []
        self.ops: list[_Op] = []

    # ------------------------------------------------------------ errors
    def fail(self, tok: Token, expected: str) -> SlugsFormatError:
        if tok.kind == "end":
            return SlugsFormatError(f"the formula ends too early: expected {expected}", tok.span)
        return SlugsFormatError(f"unexpected '{tok.text}': expected {expected}", tok.span)

    def unexpected(self, tok: Token) -> SlugsFormatError:
        opener = next((op for op in reversed(self.ops) if op.prec == 0), None)
        if opener is None:
            return self.fail(tok, "an operator or the end of the line")
        return self.fail(tok, f"'{_CLOSING[opener.text]}' to close the '{opener.text}' at "
                              f"column {opener.span.column}")

    def temporal(self, tok: Token) -> SlugsFormatError:
        return SlugsFormatError(
            f"temporal operator {_TEMPORAL[tok.text]} is outside GR(1): a section line is "
            "a state or transition formula (use next/X or primes only)",
            tok.span,
        )

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

    # ------------------------------------------------------------ the loop
    def parse_line(self) -> Expr:
        self.pos = 0
        want_operand = True
        while True:
            tok = self.tokens[self.pos]
            self.pos += 1
            if want_operand:
                want_operand = self.operand(tok)
            elif tok.kind == "end":
                return self.finish(tok)
            else:
                want_operand = self.operator(tok)

    def in_terms(self) -> bool:
        """Whether the operand to come must be an integer term (after '+' or a comparison)."""
        return bool(self.ops) and (self.ops[-1].term or self.ops[-1].prec in (_COMPARISON, _PLUS))

    def operand(self, tok: Token) -> bool:
        """Read ``tok`` where an operand starts; True while still waiting for the operand."""
        terms = self.in_terms()
        after = self.tokens[min(self.pos, len(self.tokens) - 1)]
        if (self.next_atoms and tok.text == "X" and after.kind == "ident"
                and after.text not in KEYWORDS and not after.text.endswith("'")):
            self.pos += 1
            self.values.append(self.atom(after, terms, primed=True))
            return False
        if tok.text == "(" or (tok.text == "[" and not terms):
            self.ops.append(_Op(tok.text, tok.span, 0, term=terms))
            return True
        if tok.kind == "num":
            value = IntConst(checked_int(tok.text, tok.span), span=tok.span)
            self.values.append(_Value(value, True, tok))
            return False
        if tok.kind == "ident" and tok.text not in KEYWORDS:
            self.values.append(self.atom(tok, terms))
            return False
        if terms:
            raise self.fail(tok, _IN_TERMS)
        if tok.text == "!" or tok.text in ("X", "next"):
            self.ops.append(_Op("!" if tok.text == "!" else "X", tok.span, _UNARY))
            return True
        if tok.text in _TEMPORAL and tok.kind != "num":
            raise self.temporal(tok)
        if tok.text in ("TRUE", "FALSE"):
            self.values.append(_Value(Const(tok.text == "TRUE", span=tok.span), False))
            return False
        raise self.fail(tok, _IN_FORMULAS)

    def atom(self, tok: Token, terms: bool, primed: bool = False) -> _Value:
        name = tok.text.rstrip("'")
        primed = primed or tok.text.endswith("'")
        spec_name = self.names.get(name, name)
        mark = (tok.span, spec_name) if primed else None
        if name in self.integers:
            return _Value(IntVar(spec_name, primed, span=tok.span), True, primed=mark)
        if name in self.booleans:
            if terms:
                raise SlugsFormatError(
                    f"Boolean variable '{name}' cannot be used in arithmetic; only integer "
                    "variables (name:MIN...MAX) can",
                    tok.span,
                )
            return _Value(Var(spec_name, primed, span=tok.span), False, primed=mark)
        raise self.unknown(tok)

    def operator(self, tok: Token) -> bool:
        """Read ``tok`` after a complete operand; True when an operand must follow."""
        text, top = tok.text, self.values[-1]
        if text in ("+", "-", "*"):
            if not top.is_term:
                raise self.unexpected(tok)
            if text == "-":
                raise SlugsFormatError(
                    "subtraction is not supported (SLUGS does not support it either); move "
                    "the term to the other side, e.g. 'x + 1 = y' instead of 'x = y - 1'",
                    tok.span,
                )
            if text == "*":
                raise SlugsFormatError(
                    "multiplication is not supported; write repeated additions instead",
                    tok.span,
                )
            self.ops.append(_Op("+", tok.span, _PLUS))
            return True
        if text in _COMPARE:
            self.reduce_while(lambda op: op.prec == _PLUS, tok)
            if not self.values[-1].is_term or (self.ops and (
                    self.ops[-1].term or self.ops[-1].prec == _COMPARISON)):
                raise self.unexpected(tok)
            self.ops.append(_Op(text, tok.span, _COMPARISON))
            return True
        if text in _BINARY or (tok.kind == "ident" and text in ("U", "W")):
            self.to_formula(tok)
            if text in ("U", "W"):
                raise self.temporal(tok)
            prec = _BINARY[text]
            self.reduce_while(lambda op: op.prec >= prec and not (
                op.text == text and text in ("&", "|")), tok)
            if self.ops and self.ops[-1].text == text and text in ("&", "|"):
                self.ops[-1].count += 1
            else:
                self.ops.append(_Op(text, tok.span, prec))
            return True
        if text in (")", "]"):
            self.close(tok)
            return False
        self.lone_term(tok)
        raise self.unexpected(tok)

    def lone_term(self, tok: Token) -> None:
        """A term ends at ``tok`` without a comparison: 0 and 1 are constants, else an error."""
        if not (self.ops and self.ops[-1].prec == _COMPARISON):
            self.reduce_while(lambda op: op.prec == _PLUS, tok)
            opener = next((op for op in reversed(self.ops) if op.prec == 0), None)
            if self.values[-1].is_term and not (opener is not None and opener.term):
                self.formula(self.values[-1], tok)

    def close(self, tok: Token) -> None:
        if not any(op.prec == 0 for op in self.ops):
            self.lone_term(tok)
            raise SlugsFormatError(
                f"unexpected '{tok.text}' with no matching opening bracket", tok.span
            )
        self.reduce_while(lambda op: op.prec > 0, tok)
        opener = self.ops[-1]
        if _CLOSING[opener.text] != tok.text:
            raise self.unexpected(tok)
        if opener.text == "[":
            self.values[-1] = self.formula(self.values[-1], tok)
        self.ops.pop()

    def finish(self, tok: Token) -> Expr:
        self.reduce_while(lambda op: op.prec > 0, tok)
        if self.ops:
            opener = self.ops[-1]
            raise SlugsFormatError(
                f"missing '{_CLOSING[opener.text]}' to close the '{opener.text}' at column "
                f"{opener.span.column}",
                opener.span,
            )
        return cast(Expr, self.formula(self.values[-1], tok).node)

    # ------------------------------------------------------------ reductions
    def to_formula(self, tok: Token) -> None:
        """Complete the sum or comparison on top; a Boolean operator ``tok`` follows it."""
        self.reduce_while(lambda op: op.prec >= _COMPARISON, tok)
        if self.ops and self.ops[-1].term:
            raise self.unexpected(tok)
        self.values[-1] = self.formula(self.values[-1], tok)

    def formula(self, value: _Value, tok: Token) -> _Value:
        """``value`` as a formula: 0 and 1 are constants, other terms need a comparison."""
        if not value.is_term:
            return value
        number = value.numeral
        if number is not None and number.text in ("0", "1"):
            return _Value(Const(number.text == "1", span=number.span), False)
        if number is not None:
            raise SlugsFormatError(
                f"the number {number.text} is not a formula; compare it with an integer "
                f"variable, e.g. 'x = {number.text}'",
                number.span,
            )
        raise self.fail(tok, "a comparison (=, !=, <, <=, >, >=) after an integer expression")

    def reduce_while(self, more: Callable[[_Op], bool], tok: Token) -> None:
        while self.ops and self.ops[-1].prec > 0 and more(self.ops[-1]):
            self.reduce(self.ops.pop(), tok)

    def reduce(self, op: _Op, tok: Token) -> None:
        """Apply ``op`` to its operands on top of the value stack (``tok`` is the next token)."""
        need = op.count if op.text in ("&", "|") else 1 if op.prec == _UNARY else 2
        args = self.values[-need:]
        del self.values[-need:]
        nested = _first([a.nested for a in args])
        mark = _first([a.primed for a in args])
        if op.prec in (_PLUS, _COMPARISON):
            left, right = cast(Term, args[0].node), cast(Term, args[1].node)
            if op.prec == _PLUS:
                self.values.append(_Value(Add(left, right, span=op.span), True, None,
                                          nested, mark))
            else:
                node = Compare(op.text, left, right, span=op.span)
                self.values.append(_Value(node, False, None, nested, mark))
            return
        parts = [cast(Expr, self.formula(a, tok).node) for a in args]
        result: Expr
        if op.text == "X":
            self.values.append(self.next_of(op, parts[0], nested, mark))
            return
        if op.text == "!":
            result = Not(parts[0], span=op.span)
        elif op.text in ("&", "|"):
            result = (And if op.text == "&" else Or)(tuple(parts), span=op.span)
        else:
            kind = {"<->": Iff, "->": Implies, "^": Xor}[op.text]
            result = kind(parts[0], parts[1], span=op.span)
        self.values.append(_Value(result, False, None, nested, mark))

    def next_of(self, op: _Op, arg: Expr, nested: _Mark, mark: _Mark) -> _Value:
        first = _first([nested, mark])
        if first is not None and first is nested:
            raise SlugsFormatError(
                "'next' inside 'next' is outside GR(1): a formula may look one step ahead only",
                first[0],
            )
        if first is not None:
            raise SlugsFormatError(
                f"'{first[1]}' is already a next-state value; 'next' cannot apply twice",
                first[0],
            )
        return _Value(primed(arg), False, None, (op.span, "next"), None)


def parse_infix(
    text: str, filename: str, line: int, booleans: set[str], integers: Mapping[str, object],
    names: Mapping[str, str] | None = None, next_atoms: bool = False,
) -> Expr:
    """Parse one infix formula line; ``next``/``X`` are pushed into primes.

    ``names`` maps the written names to the spec's names; ``next_atoms`` reads ``X x`` as
    the atom ``x'`` (the readable LTL text).  Any nesting depth is fine.
    """
    tokens = tokenize(text, filename, line)
    return InfixParser(tokens, booleans, integers, names, next_atoms).parse_line()
