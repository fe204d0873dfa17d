"""The formula IR: immutable propositional/integer formulas with primes (next-state copies).

Nodes are frozen dataclasses; the optional ``span`` rides along but does not take
part in equality or hashing, so tests compare trees structurally.  Hashes are
cached, because readers of ``.slugsin`` memory buffers (``$``/``?``) build DAGs
with heavy sharing.  ``Next``/``Always``/``Eventually`` exist only so front ends
can represent user formulas before they are sorted into GR(1) sections; the
sections of a :class:`~gaitc.ir.spec.GR1Spec` contain none of them
(:func:`push_next` removes ``Next`` by priming variables).

The node base class and the traversal live in :mod:`gaitc.ir.traversal`; priming,
substitution and simplification here are folds over it, so formulas of any depth
need no recursion.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import NoReturn, cast

from gaitc.diagnostics import FormulaError, Span
from gaitc.ir.traversal import Node as Node
from gaitc.ir.traversal import fold, rebuild

_SPAN = field(default=None, compare=False, repr=False, kw_only=True)


# ---------------------------------------------------------------- integer terms
@dataclass(frozen=True, eq=False)
class Term(Node):
    """An integer-valued term (only inside a :class:`Compare`)."""


@dataclass(frozen=True, eq=False)
class IntConst(Term):
    """An integer literal."""

    value: int
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class IntVar(Term):
    """An integer variable, ``primed`` for its next-state copy."""

    name: str
    primed: bool = False
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Add(Term):
    """The sum of two integer terms."""

    left: Term
    right: Term
    span: Span | None = _SPAN


# ---------------------------------------------------------------- Boolean formulas
@dataclass(frozen=True, eq=False)
class Expr(Node):
    """A Boolean formula."""


@dataclass(frozen=True, eq=False)
class Const(Expr):
    """``true`` or ``false``."""

    value: bool
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Var(Expr):
    """A Boolean variable, ``primed`` for its next-state copy."""

    name: str
    primed: bool = False
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Not(Expr):
    """Negation."""

    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class And(Expr):
    """Conjunction of ``args`` (``true`` when there are none)."""

    args: tuple[Expr, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Or(Expr):
    """Disjunction of ``args`` (``false`` when there are none)."""

    args: tuple[Expr, ...]
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Xor(Expr):
    """Exclusive or."""

    left: Expr
    right: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Iff(Expr):
    """Equivalence."""

    left: Expr
    right: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Implies(Expr):
    """Implication, ``left`` → ``right``."""

    left: Expr
    right: Expr
    span: Span | None = _SPAN


COMPARE_OPS = ("=", "!=", "<", "<=", ">", ">=")


@dataclass(frozen=True, eq=False)
class Compare(Expr):
    """A comparison of two integer terms; ``op`` is one of :data:`COMPARE_OPS`."""

    op: str
    left: Term
    right: Term
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Next(Expr):
    """``next(arg)``; removed by :func:`push_next` before a formula enters a GR(1) section."""

    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Always(Expr):
    """``always arg``; only in front-end formulas, sorted into sections by the compiler."""

    arg: Expr
    span: Span | None = _SPAN


@dataclass(frozen=True, eq=False)
class Eventually(Expr):
    """``eventually arg``; only in front-end formulas, sorted into sections by the compiler."""

    arg: Expr
    span: Span | None = _SPAN


TRUE = Const(True)
FALSE = Const(False)


# ---------------------------------------------------------------- checked dispatch
#: Every kind of integer term, and every kind of Boolean formula. A dispatch over formula
#: nodes is a ``match`` over :func:`term_kind` or :func:`formula_kind` that ends in
#: ``case _: unreachable(node)``: mypy then reports any kind a dispatch forgets.
TermKind = IntConst | IntVar | Add
FormulaKind = (Const | Var | Not | And | Or | Xor | Iff | Implies | Compare | Next | Always
               | Eventually)
TERM_KINDS = (IntConst, IntVar, Add)
FORMULA_KINDS = (Const, Var, Not, And, Or, Xor, Iff, Implies, Compare, Next, Always,
                 Eventually)


def term_kind(node: Node) -> TermKind:
    """``node`` as one of the term kinds (the traversal hands out the base class)."""
    if not isinstance(node, TERM_KINDS):
        raise TypeError(f"not an integer term: {type(node).__name__}")
    return node


def formula_kind(node: Node) -> FormulaKind:
    """``node`` as one of the Boolean formula kinds."""
    if not isinstance(node, FORMULA_KINDS):
        raise TypeError(f"not a Boolean formula: {type(node).__name__}")
    return node


def node_kind(node: Node) -> TermKind | FormulaKind:
    """``node`` as any kind of the IR."""
    return term_kind(node) if isinstance(node, Term) else formula_kind(node)


def unreachable(node: NoReturn) -> NoReturn:
    """The last case of a checked dispatch (over formula nodes, or over the statements of
    :data:`ltlcompiler.syntax.Statement`): mypy proves it is never reached."""
    raise AssertionError(f"a checked dispatch forgot {type(node).__name__}")


# ---------------------------------------------------------------- construction helpers
def conj(items: Iterable[Expr], span: Span | None = None) -> Expr:
    """Conjunction of ``items``; ``TRUE`` when empty, the item itself when single."""
    args = tuple(items)
    if not args:
        return TRUE
    if len(args) == 1:
        return args[0]
    return And(args, span=span)


def disj(items: Iterable[Expr], span: Span | None = None) -> Expr:
    """Disjunction of ``items``; ``FALSE`` when empty, the item itself when single."""
    args = tuple(items)
    if not args:
        return FALSE
    if len(args) == 1:
        return args[0]
    return Or(args, span=span)


def walk(node: Node) -> Iterator[Node]:
    """Every node reachable from ``node``, each shared node once (pre-order)."""
    seen: set[int] = set()
    stack: list[Node] = [node]
    while stack:
        current = stack.pop()
        if id(current) in seen:
            continue
        seen.add(id(current))
        yield current
        stack.extend(reversed(current.children()))


def atoms(node: Node) -> set[tuple[str, bool]]:
    """The ``(name, primed)`` pairs of every Boolean or integer variable in ``node``
    (:func:`walk` written out: specs with large formulas ask for it per clause)."""
    out: set[tuple[str, bool]] = set()
    seen: set[int] = set()
    stack: list[Node] = [node]
    while stack:
        current = stack.pop()
        key = id(current)
        if key in seen:
            continue
        seen.add(key)
        if isinstance(current, (Var, IntVar)):
            out.add((current.name, current.primed))
        else:
            stack.extend(current.children())
    return out


def has_primes(node: Node) -> bool:
    """Whether ``node`` mentions a next-state variable or a ``Next``."""
    return any(
        isinstance(n, Next) or (isinstance(n, (Var, IntVar)) and n.primed) for n in walk(node)
    )


# ---------------------------------------------------------------- transformations
def _reject_temporal(node: Node) -> None:
    if isinstance(node, (Always, Eventually)):
        word = "always" if isinstance(node, Always) else "eventually"
        raise FormulaError(
            f"'{word}' cannot appear inside another formula here: GR(1) allows it only "
            "at the top of an assumption or guarantee",
            node.span,
        )


def _primed(node: Node) -> Node | None:
    """The replacement of ``node`` under ``next`` (:func:`rebuild`): variables primed."""
    if isinstance(node, Next):
        raise FormulaError(
            "'next' inside 'next' is outside GR(1): a formula may look one step ahead only",
            node.span,
        )
    _reject_temporal(node)
    if isinstance(node, (Var, IntVar)):
        if node.primed:
            raise FormulaError(
                f"'{node.name}' is already a next-state value; 'next' cannot apply twice",
                node.span,
            )
        return type(node)(node.name, True, span=node.span)
    return None


def _unprimed(node: Node) -> Node | None:
    """The replacement of ``node`` outside ``next``: a ``Next`` by its primed argument."""
    if isinstance(node, Next):
        return rebuild(node.arg, _primed)
    _reject_temporal(node)
    return None


def push_next(expr: Expr) -> Expr:
    """Replace ``Next(φ)`` by ``φ`` with every variable primed.

    Raises :class:`FormulaError` for ``next`` inside ``next`` (or over an already
    primed variable) and for ``always``/``eventually`` anywhere inside: neither is
    expressible in a GR(1) section.
    """
    return rebuild(expr, _unprimed)


def prime(expr: Expr) -> Expr:
    """``expr`` one step later: every variable primed (equivalent to ``push_next(Next(expr))``)."""
    return push_next(Next(expr, span=expr.span))


def substitute(expr: Expr, mapping: Mapping[tuple[str, bool], Expr]) -> Expr:
    """Replace Boolean variables ``(name, primed)`` by formulas."""

    def replace(node: Node) -> Node | None:
        if isinstance(node, Var):
            return mapping.get((node.name, node.primed))
        return None

    return rebuild(expr, replace)


def _negated(expr: Expr) -> Expr:
    """``simplify(Not(expr))`` for an already simplified ``expr`` (simplify is idempotent)."""
    if isinstance(expr, Const):
        return Const(not expr.value)
    if isinstance(expr, Not):
        return expr.arg
    return Not(expr)


def _simplified(node: Node, kids: list[Node]) -> Node:
    """One step of :func:`simplify`: ``node`` over its already simplified children."""
    args = cast(list[Expr], kids)  # the children of a Boolean operator are formulas
    if isinstance(node, Not):
        arg = args[0]
        if isinstance(arg, Const):
            return Const(not arg.value, span=node.span)
        if isinstance(arg, Not):
            return arg.arg
        return Not(arg, span=node.span)
    if isinstance(node, (And, Or)):
        unit, zero = (True, False) if isinstance(node, And) else (False, True)
        out: list[Expr] = []
        seen: set[Expr] = set()
        for c in args:
            parts = c.args if isinstance(c, (And, Or)) and type(c) is type(node) else (c,)
            for p in parts:
                if isinstance(p, Const):
                    if p.value == zero:
                        return Const(zero, span=node.span)
                    continue
                if p not in seen:
                    seen.add(p)
                    out.append(p)
        for p in out:
            if Not(p) in seen:
                return Const(zero, span=node.span)
        if not out:
            return Const(unit, span=node.span)
        if len(out) == 1:
            return out[0]
        return type(node)(tuple(out), span=node.span)
    if isinstance(node, (Xor, Iff, Implies)):
        left, right = args
        if isinstance(node, Implies):
            if isinstance(left, Const):
                return right if left.value else Const(True, span=node.span)
            if isinstance(right, Const):
                return Const(True, span=node.span) if right.value else _negated(left)
            return Implies(left, right, span=node.span)
        flip = isinstance(node, Xor)
        if isinstance(left, Const) and isinstance(right, Const):
            return Const((left.value == right.value) != flip, span=node.span)
        for a, b in ((left, right), (right, left)):
            if isinstance(a, Const):
                keep = a.value != flip
                return b if keep else _negated(b)
        return type(node)(left, right, span=node.span)
    return node.with_children(kids)


def simplify(expr: Expr) -> Expr:
    """Fold constants, flatten nested ``And``/``Or``, drop double negations and duplicates.

    The result has the same truth value as ``expr`` under every valuation.
    """
    result = fold(expr, _simplified)
    assert isinstance(result, Expr)
    return result
